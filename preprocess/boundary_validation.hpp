// Checks that the boundary of the body encloses a region, and orients it: every facet's normal
// (2-D: right of a->b, 3-D: (b-a)x(c-a)) points out of the body afterwards. Bad geometry is an
// InputError naming the file and a place near the problem.
//   2-D: every boundary vertex is on exactly two segments, no two segments cross (exact sweep);
//        loops are oriented with the body on
//        their left (outer loops counter-clockwise, holes clockwise; nesting by exact parity).
//   3-D: every edge is on exactly two triangles (closed, manifold), no two triangles intersect
//        except along shared edges (CGAL does_self_intersect), and the components are oriented
//        to bound a volume (CGAL orient_to_bound_a_volume, which handles cavities).
#pragma once
#include <string>

#include "preprocess/geometry_model.hpp"

namespace mppm::pre {

void validate_and_orient_boundary(FacetMesh& boundary, const std::string& file);

// Unit outward normal of a facet of an oriented boundary.
Vec3 facet_normal(const FacetMesh& boundary, std::size_t facet);

// Length (2-D) or area (3-D) of a facet.
double facet_measure(const FacetMesh& boundary, std::size_t facet);

}  // namespace mppm::pre
