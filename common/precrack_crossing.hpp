// Pre-crack cuts (docs/theory.md section 8): does the straight bond between two material points cross a
// pre-crack (2-D: segments of a curve, 3-D: triangles of a surface, as stored in
// PointCloud::precrack_vertices)? Exact predicates (CGAL), so the same bonds are cut on every
// machine and for every thread count. Free of gmsh so that the solver can use it.
//
// Rule: the bond and the pre-crack are closed sets; a bond that touches a pre-crack (even at its
// tip or with one end point on it) counts as crossing. Lattice points exactly on a zero-width
// pre-crack therefore lose the bonds that touch it: put pre-cracks between lattice rows. Likewise a
// pre-crack that ends exactly on a cell face (the tip at x = k dx for points at (i + 1/2) dx) leaves
// the bonds crossing its line exactly at the tip to the rounding of the coordinates: two notches
// placed alike can then be cut differently. End pre-cracks a little off the faces
// (geometry/kalthoff_winkler_plate.geo: 10 um).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace mppm {

using Point3 = std::array<double, 3>;

// Brute force over every pre-crack element (tests, a handful of queries). `dimension` 2 uses x, y
// of 2-vertex segments; 3 uses 3-vertex triangles. Degenerate elements cut nothing.
bool bond_crosses_precrack(const Point3& a, const Point3& b, int dimension,
                           const std::vector<double>& precrack_vertices);

// The same test for many bonds: pre-crack elements binned on a uniform grid of `cell_size`
// (pass the horizon: a bond then touches at most 2^d cells per axis). Immutable after
// construction, so concurrent `crosses` calls from OpenMP threads are safe.
class PrecrackIndex {
 public:
  PrecrackIndex(int dimension, const std::vector<double>& precrack_vertices, double cell_size);

  bool crosses(const Point3& a, const Point3& b) const;
  // False when no bond from `a` of length up to `reach` can touch a pre-crack: the box of half-width
  // `reach` around `a` misses the bounding box of all elements. A test per point that spares most
  // points the test of each of their bonds: `crosses` is false for them too.
  bool may_cross_within(const Point3& a, double reach) const;
  bool empty() const { return elements_ == 0; }
  std::size_t element_count() const { return elements_; }

 private:
  struct CellEntry {
    std::array<std::int64_t, 3> cell;
    std::int32_t element;
  };
  bool element_crosses(std::int32_t element, const Point3& a, const Point3& b) const;

  int dimension_;
  double cell_size_;
  std::vector<double> vertices_;  // valid (non-degenerate) elements only
  std::size_t elements_ = 0;
  std::array<double, 3> low_{}, high_{};  // bounding box of all elements
  std::vector<CellEntry> entries_;        // sorted by cell
};

}  // namespace mppm
