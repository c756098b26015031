// The mid-thickness layer of a 3-D body: the lattice plane the crack angle of a 3-D run is
// measured on (postprocess/README.md "Crack angle", 3-D runs). A crack through the thickness of
// a plate crosses it as it crosses a 2-D plane-strain slice, so the 2-D method applies there.
#pragma once
#include <cstddef>
#include <vector>

namespace mppm::post {

struct MidThicknessLayer {
  double z = 0.0;              // the layer's height [m]
  std::vector<char> include;   // the body points of the layer (nonzero)
  std::vector<double> flat_z;  // every point's z set to the layer's: the 2-D trackers see one plane
  std::size_t points = 0;      // body points in the layer
};

// The body points (`body` nonzero) whose z lies within dx/4 of the body point z nearest the
// middle of the body's z extent (of two planes equally near, the lower): one lattice plane.
// Throws std::invalid_argument on arrays of different lengths, no body point or dx <= 0.
MidThicknessLayer mid_thickness_layer(const std::vector<double>& z, const std::vector<char>& body, double spacing);

}  // namespace mppm::post
