// Selector resolution (see boundary_selection.hpp).
#include "preprocess/boundary_selection.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/input_error.hpp"

namespace mppm::pre {
namespace {

const char* facet_kind(int dimension) { return dimension == 2 ? "curve" : "surface"; }

std::string list(const std::vector<int>& tags) {
  std::ostringstream s;
  for (std::size_t i = 0; i < tags.size(); ++i) {
    if (i == 20) {
      s << ", ... (" << tags.size() << " in all)";
      break;
    }
    s << (i ? ", " : "") << tags[i];
  }
  return s.str();
}

// Entity tags of dimension d-1 named by the selector's physical group or entity list.
std::vector<int> selected_entities(const Selector& selector, const GeometryModel& model,
                                   const std::vector<int>& allowed, const std::string& context) {
  const int d = model.dimension;
  std::vector<int> tags;
  if (!selector.physical_group.empty()) {
    bool found = false;
    for (const PhysicalGroup& g : model.groups) {
      if (g.name != selector.physical_group) continue;
      if (g.dimension != d - 1)
        throw InputError(context + ": physical group '" + g.name + "' in " + model.file + " is a " +
                         (g.dimension == 3   ? "volume"
                          : g.dimension == 2 ? "surface"
                          : g.dimension == 1 ? "curve"
                                             : "point") +
                         " group (expected a physical " + facet_kind(d) + " in a " + std::to_string(d) +
                         "-D scene; available: " + model.describe_groups() + ")");
      found = true;
      tags.insert(tags.end(), g.entities.begin(), g.entities.end());
    }
    if (!found)
      throw InputError(context + ": unknown physical group '" + selector.physical_group + "' in " + model.file +
                       " (available: " + model.describe_groups() + ")");
  }
  for (int tag : selector.entities) {
    if (!std::binary_search(model.facet_entities.begin(), model.facet_entities.end(), tag))
      throw InputError(context + ": " + model.file + " has no " + facet_kind(d) + " entity " + std::to_string(tag) +
                       " (" + facet_kind(d) + " entities: " + list(model.facet_entities) + ")");
    tags.push_back(tag);
  }
  for (int tag : tags)
    if (!std::binary_search(allowed.begin(), allowed.end(), tag))
      throw InputError(context + ": " + facet_kind(d) + " entity " + std::to_string(tag) + " of " + model.file +
                       " is not on the boundary of the body (boundary entities: " + list(allowed) + ")");
  std::sort(tags.begin(), tags.end());
  tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
  return tags;
}

bool facet_in_box(const FacetMesh& mesh, std::size_t f, const std::array<std::array<double, 3>, 2>& box,
                  double tolerance) {
  for (int c = 0; c < mesh.dimension; ++c) {
    const Vec3& p = mesh.vertex(f, c);
    for (int a = 0; a < mesh.dimension; ++a)
      if (p[a] < std::min(box[0][a], box[1][a]) - tolerance || p[a] > std::max(box[0][a], box[1][a]) + tolerance)
        return false;
  }
  return true;
}

double model_size(const FacetMesh& mesh) {
  double size = 0.0;
  for (const Vec3& v : mesh.vertices) size = std::max({size, std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
  return size;
}

std::string no_selection(const Selector& selector, const GeometryModel& model, const std::string& context,
                         const char* what) {
  return context + ": " + selector.describe() + " selects no " + what + " of " + model.file +
         " (physical groups: " + model.describe_groups() + ")";
}

}  // namespace

std::vector<std::size_t> select_boundary_facets(const Selector& selector, const GeometryModel& model,
                                                const FacetMesh& boundary, const std::string& context) {
  std::vector<std::size_t> facets;
  if (selector.box) {
    const double tolerance = 1e-9 * std::max(model_size(boundary), 1e-300);
    for (std::size_t f = 0; f < boundary.facet_count(); ++f)
      if (facet_in_box(boundary, f, *selector.box, tolerance)) facets.push_back(f);
  } else {
    const std::vector<int> tags = selected_entities(selector, model, model.boundary_entities, context);
    for (std::size_t f = 0; f < boundary.facet_count(); ++f)
      if (std::binary_search(tags.begin(), tags.end(), boundary.entity[f])) facets.push_back(f);
  }
  if (facets.empty()) throw InputError(no_selection(selector, model, context, "part of the body boundary"));
  return facets;
}

std::vector<double> select_precrack_vertices(const Selector& selector, const GeometryModel& model,
                                             const std::string& context) {
  const FacetMesh& mesh = model.facets;
  std::vector<double> vertices;
  auto add = [&](std::size_t f) {
    for (int c = 0; c < mesh.dimension; ++c)
      for (int a = 0; a < 3; ++a) vertices.push_back(mesh.vertex(f, c)[a]);
  };
  if (selector.box) {
    const double tolerance = 1e-9 * std::max(model_size(mesh), 1e-300);
    for (std::size_t f = 0; f < mesh.facet_count(); ++f)
      if (!std::binary_search(model.boundary_entities.begin(), model.boundary_entities.end(), mesh.entity[f]) &&
          facet_in_box(mesh, f, *selector.box, tolerance))
        add(f);
  } else {
    const std::vector<int> tags = selected_entities(selector, model, model.facet_entities, context);
    for (std::size_t f = 0; f < mesh.facet_count(); ++f)
      if (std::binary_search(tags.begin(), tags.end(), mesh.entity[f])) add(f);
  }
  if (vertices.empty())
    throw InputError(
        no_selection(selector, model, context, model.dimension == 2 ? "pre-crack curve" : "pre-crack surface"));
  return vertices;
}

}  // namespace mppm::pre
