// From a scene Selector (physical group name, gmsh entity tags, or box) to the facets it means
// (docs/scene.md). An unknown group or an empty selection is an InputError that names the scene
// entry and the geometry file and lists what the geometry does offer.
#pragma once
#include <string>
#include <vector>

#include "common/scene.hpp"
#include "preprocess/geometry_model.hpp"

namespace mppm::pre {

// Indices into `boundary` (the oriented body boundary) of the facets a boundary condition
// selects. `context` prefixes messages, e.g. "scene.yaml:31: boundary_conditions[2]".
std::vector<std::size_t> select_boundary_facets(const Selector& selector, const GeometryModel& model,
                                                const FacetMesh& boundary, const std::string& context);

// Pre-crack geometry (flattened x y z per vertex, 2 vertices per segment in 2-D, 3 per
// triangle in 3-D) of the entities of dimension d-1 a selector means. A box selects only
// entities that are not on the body boundary (a pre-crack lies inside the body).
std::vector<double> select_precrack_vertices(const Selector& selector, const GeometryModel& model,
                                             const std::string& context);

}  // namespace mppm::pre
