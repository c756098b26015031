// POST_DIR/view.py: a ParaView Python state of the post directory, so that
// `paraview --script=POST_DIR/view.py` (or `pvbatch POST_DIR/view.py --screenshot OUT.png`) shows
// the body as the figures do: results.pvd read relative to the script, boundary-layer and
// detached points hidden, warped by displacement, coloured by the case's main field, at the last
// time (postprocess/README.md, "Opening a run in ParaView").
#pragma once
#include <string>
#include <vector>

namespace mppm::post {

struct ParaViewStateSettings {
  std::string field;        // the array to colour by (view_field)
  double warp_scale = 1.0;  // --warp-scale, as in the figures
  double spacing = 0.0;     // dx [m]: the points are drawn as discs of radius dx / sqrt(2)
  int dimension = 2;        // 2: a 2-D camera looking down z
};

// The case's main field among the frame's arrays: damage when present, else
// plastic_shear_strain, else pore_pressure, else displacement (coloured by its magnitude); empty
// when none is there.
std::string view_field(const std::vector<std::string>& array_names);

// The text of view.py for these settings.
std::string paraview_state_script(const ParaViewStateSettings& settings);

// Writes POST_DIR/view.py atomically (complete or not there).
void write_paraview_state(const std::string& post_directory, const ParaViewStateSettings& settings);

}  // namespace mppm::post
