// The preprocessing pipeline (see preprocessor.hpp): read and mesh, validate and orient the
// boundary, classify the lattice, add the layers, tag loaded points, collect pre-cracks.
#include "preprocess/preprocessor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "common/input_error.hpp"
#include "common/lattice_offsets.hpp"
#include "common/memory_estimate.hpp"
#include "common/progress.hpp"  // format_bytes
#include "preprocess/boundary_layers.hpp"
#include "preprocess/boundary_selection.hpp"
#include "preprocess/boundary_validation.hpp"
#include "preprocess/geometry_model.hpp"
#include "preprocess/inside_test.hpp"
#include "preprocess/lattice.hpp"
#include "preprocess/site_order.hpp"

namespace mppm::pre {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string scene_context(const Scene& scene, const BoundaryCondition& bc, std::size_t index) {
  return scene.path + ":" + std::to_string(bc.line) + ": boundary_conditions[" + std::to_string(index) + "]";
}

std::string boundary_label(const BoundaryCondition& bc, std::size_t index) {
  if (!bc.name.empty()) return bc.name;
  if (!bc.selector.physical_group.empty()) return bc.selector.physical_group;
  return "bc" + std::to_string(index + 1);
}

GeometryRequest geometry_request(const Scene& scene, const PreprocessOptions& options) {
  const int d = scene.dimension;
  GeometryRequest request;
  request.file = scene.geometry.file;
  request.dimension = d;
  request.unit = scene.geometry.unit;
  const double factor = options.facet_size_factor > 0 ? options.facet_size_factor : (d == 2 ? 0.25 : 3.0);
  request.facet_size = factor * scene.geometry.spacing;
  request.verbose = options.verbose;
  return request;
}

struct Box {
  Vec3 low, high;
};

// Bounding box of the body from the boundary vertices (exact file coordinates; CAD bounding
// boxes are padded by the kernel's tolerance).
Box body_box(const FacetMesh& boundary, const GeometryModel& model, int d, double facet_size) {
  Vec3 low{HUGE_VAL, HUGE_VAL, HUGE_VAL}, high{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t f = 0; f < boundary.facet_count(); ++f)
    for (int c = 0; c < d; ++c)
      for (int a = 0; a < 3; ++a) {
        low[a] = std::min(low[a], boundary.vertex(f, c)[a]);
        high[a] = std::max(high[a], boundary.vertex(f, c)[a]);
      }
  // Prefer the CAD box where it encloses the facets and differs from their box by less than
  // one facet (the most a vertex box can miss of a curved boundary): the lattice is then centred
  // on the true extent, e.g. symmetric on a cylinder whose facet vertices miss one side by a sag.
  if (model.has_cad_box) {
    bool agrees = true;
    for (int a = 0; a < d; ++a)
      agrees = agrees && model.cad_low[a] <= low[a] && model.cad_high[a] >= high[a] &&
               low[a] - model.cad_low[a] <= facet_size && model.cad_high[a] - high[a] <= facet_size;
    if (agrees)
      for (int a = 0; a < d; ++a) {
        low[a] = model.cad_low[a];
        high[a] = model.cad_high[a];
      }
  }
  return {low, high};
}

void check_body_wider_than_spacing(const Scene& scene, const GeometryModel& model, const Box& box) {
  const double dx = scene.geometry.spacing;
  static const char* axes = "xyz";
  for (int a = 0; a < scene.dimension; ++a)
    if (box.high[a] - box.low[a] < dx) {
      std::ostringstream s;
      s << scene.path << ": geometry.spacing (dx = " << dx << " m) is larger than the body " << model.file
        << " (extent " << box.high[a] - box.low[a] << " m along " << axes[a] << "): choose dx smaller than the body";
      throw InputError(s.str());
    }
}

// The facets each boundary condition selects, and the layers they make: kinematic and drained
// (pore_pressure) boundaries one horizon deep outside the body, loaded ones (traction, pressure,
// fluid_flux) traction_depth (default dx) deep inside it. A fluid condition with the selection of
// a mechanical one shares its points instead (docs/stages.md "Boundaries").
struct BoundaryLayers {
  std::vector<std::vector<std::size_t>> selected;  // per boundary condition
  std::vector<LayerRequest> kinematic, drained, loaded, fluxes;
  std::vector<std::optional<std::size_t>> shares;  // per boundary condition: the condition whose points it takes
};

double layer_depth(const Scene& scene, const BoundaryCondition& bc) {
  if (!has_loaded_depth(bc.type)) return scene.geometry.horizon();
  return bc.traction_depth > 0 ? bc.traction_depth : scene.geometry.spacing;
}

// The kind of points a condition is carried by: a kinematic layer, a drained layer, loaded points
// (traction, pressure) or fed points (fluid flux).
enum class Carrier { kinematic, drained, loaded, fed };
Carrier carrier(BoundaryType type) {
  if (is_kinematic(type)) return Carrier::kinematic;
  if (type == BoundaryType::pore_pressure) return Carrier::drained;
  return type == BoundaryType::fluid_flux ? Carrier::fed : Carrier::loaded;
}

// Two conditions with the same selection: a drained one shares a kinematic layer, a flux shares
// loaded points (with the same depth); two of one kind would compete for the same points, the
// later getting none, so they are refused here with the reason (the scene reader refuses two
// fluid conditions already).
std::vector<std::optional<std::size_t>> shared_points(const Scene& scene) {
  const auto& conditions = scene.boundary_conditions;
  std::vector<std::optional<std::size_t>> shares(conditions.size());
  for (std::size_t k = 0; k < conditions.size(); ++k)
    for (std::size_t j = 0; j < conditions.size(); ++j) {
      const BoundaryCondition &a = conditions[k], &b = conditions[j];
      if (j == k || a.selector.fingerprint() != b.selector.fingerprint()) continue;
      const Carrier ca = carrier(a.type), cb = carrier(b.type);
      const std::string context = scene_context(scene, a, k) + ": " + to_string(a.type) + " on " +
                                  a.selector.describe() + ", the selection of boundary_conditions[" +
                                  std::to_string(j) + "] ('" + b.name + "', " + to_string(b.type) + ")";
      if ((ca == Carrier::drained && cb == Carrier::kinematic) || (ca == Carrier::fed && cb == Carrier::loaded)) {
        if (ca == Carrier::fed && std::abs(layer_depth(scene, a) - layer_depth(scene, b)) >
                                      1e-9 * std::max(layer_depth(scene, a), layer_depth(scene, b)))
          throw InputError(context + ": a fluid flux takes the loaded points of that condition, so its depth (" +
                           std::to_string(layer_depth(scene, a)) + " m) must be that condition's (" +
                           std::to_string(layer_depth(scene, b)) + " m)");
        shares[k] = j;
      } else if (ca == cb && j < k) {
        throw InputError(context + ": both would be carried by the same " +
                         (ca == Carrier::kinematic ? std::string("layer points (one kinematic condition per layer: "
                                                                 "prescribe the components in one condition, the "
                                                                 "others free)")
                                                   : std::string("loaded points (one traction or pressure per "
                                                                 "boundary: add the loads into one condition)")));
      }
    }
  return shares;
}

BoundaryLayers select_boundaries(const Scene& scene, const GeometryModel& model, const FacetMesh& boundary) {
  BoundaryLayers layers;
  layers.selected.resize(scene.boundary_conditions.size());
  layers.shares = shared_points(scene);
  for (std::size_t b = 0; b < scene.boundary_conditions.size(); ++b) {
    const BoundaryCondition& bc = scene.boundary_conditions[b];
    layers.selected[b] = select_boundary_facets(bc.selector, model, boundary, scene_context(scene, bc, b));
    if (layers.shares[b]) continue;
    LayerRequest layer;
    layer.boundary = static_cast<std::int32_t>(b + 1);
    layer.facets = layers.selected[b];
    layer.depth = layer_depth(scene, bc);
    switch (carrier(bc.type)) {
      case Carrier::kinematic:
        layers.kinematic.push_back(layer);
        break;
      case Carrier::drained:
        layers.drained.push_back(layer);
        break;
      case Carrier::loaded:
        layers.loaded.push_back(layer);
        break;
      case Carrier::fed:
        layers.fluxes.push_back(layer);
        break;
    }
  }
  return layers;
}

// The fluid's tags where the mechanical ones leave a point free: a drained layer takes no point
// of a kinematic layer, a flux no point a traction or pressure loads, so that the mechanics of a
// run are those without the fluid's conditions. Returns the points each boundary had in `fluid`
// before (to tell a layer that lies wholly in the others from a selection too small for dx).
std::vector<std::int64_t> add_where_free(LayerTags& mechanical, const LayerTags& fluid, std::size_t conditions) {
  std::vector<std::int64_t> tagged(conditions + 1, 0);
  for (std::size_t g = 0; g < fluid.boundary.size(); ++g) {
    if (fluid.boundary[g] == 0) continue;
    ++tagged[static_cast<std::size_t>(fluid.boundary[g])];
    if (mechanical.boundary[g] != 0) continue;
    mechanical.boundary[g] = fluid.boundary[g];
    mechanical.facet[g] = fluid.facet[g];
    mechanical.distance[g] = fluid.distance[g];
  }
  return tagged;
}

std::vector<double> precrack_vertices(const Scene& scene, const GeometryModel& model) {
  std::vector<double> vertices;
  for (std::size_t p = 0; p < scene.geometry.precracks.size(); ++p) {
    const std::vector<double> v = select_precrack_vertices(
        scene.geometry.precracks[p], model, scene.path + ": geometry.precracks[" + std::to_string(p) + "]");
    vertices.insert(vertices.end(), v.begin(), v.end());
  }
  return vertices;
}

// Points of the body (region 0) and of each layer k; throws if the body has none. Returns the
// total.
std::int64_t count_points_per_region(const Scene& scene, const GeometryModel& model,
                                     const std::vector<std::uint8_t>& inside, const LayerTags& layers,
                                     PreprocessReport& report) {
  const std::size_t nb = scene.boundary_conditions.size();
  report.points_per_region.assign(nb + 1, 0);
  for (std::size_t g = 0; g < inside.size(); ++g) {
    if (inside[g])
      ++report.points_per_region[0];
    else if (layers.boundary[g] > 0)
      ++report.points_per_region[static_cast<std::size_t>(layers.boundary[g])];
  }
  if (report.points_per_region[0] == 0)
    throw InputError(scene.path + ": no lattice point falls inside the body of " + model.file +
                     " (dx = " + std::to_string(scene.geometry.spacing) + " m is too coarse for it)");
  std::int64_t total = 0;
  for (auto c : report.points_per_region) total += c;
  return total;
}

// Body points first, then each layer k in turn: the solver finds the body as a prefix and every
// layer as a contiguous block. Within each, the points follow the Z-order curve through their
// sites (site_order.hpp: neighbours near in memory). Loaded body points carry their boundary's id
// and the normal of their nearest facet; each boundary counts its points.
void place_points(PointCloud& cloud, const LatticeGrid& grid, const std::vector<std::uint8_t>& inside,
                  const LayerTags& layers, const LayerTags& tractions, const FacetMesh& boundary,
                  const std::vector<std::int64_t>& points_per_region, std::int64_t total) {
  const std::size_t nb = points_per_region.size() - 1;
  const double dx = cloud.spacing;
  cloud.resize(static_cast<std::size_t>(total));
  const double volume = cloud.dimension == 2 ? dx * dx * cloud.thickness : dx * dx * dx;
  std::vector<std::int64_t> next(nb + 1, 0);
  for (std::size_t r = 1; r <= nb; ++r) next[r] = next[r - 1] + points_per_region[r - 1];
  cloud.boundaries.resize(nb);
  std::vector<std::uint8_t> occupied(inside.size());
  for (std::size_t g = 0; g < inside.size(); ++g) occupied[g] = inside[g] || layers.boundary[g] != 0;
  for (const std::int64_t site : sites_in_z_order(grid, occupied)) {
    const auto g = static_cast<std::size_t>(site);
    const std::int32_t region = inside[g] ? 0 : layers.boundary[g];
    const auto i = static_cast<std::size_t>(next[static_cast<std::size_t>(region)]++);
    const Vec3 p = grid.position(static_cast<std::int64_t>(g));
    cloud.x[i] = p[0];
    cloud.y[i] = p[1];
    cloud.z[i] = p[2];
    cloud.volume[i] = volume;
    cloud.region[i] = region;
    cloud.boundary_id[i] = region;
    cloud.normal_x[i] = cloud.normal_y[i] = cloud.normal_z[i] = 0.0;
    if (region == 0 && tractions.boundary[g] > 0) {
      cloud.boundary_id[i] = tractions.boundary[g];
      const Vec3 n = facet_normal(boundary, static_cast<std::size_t>(tractions.facet[g]));
      cloud.normal_x[i] = n[0];
      cloud.normal_y[i] = n[1];
      cloud.normal_z[i] = n[2];
    }
    if (cloud.boundary_id[i] > 0) ++cloud.boundaries[static_cast<std::size_t>(cloud.boundary_id[i] - 1)].point_count;
  }
}

// Name, type, selection, depth and area of each boundary; throws for one that got no point (a
// condition that shares another's points has none of its own: point_count 0). `fluid_tagged`: the
// points each fluid boundary had before the mechanical layers took theirs (add_where_free).
void describe_boundaries(const Scene& scene, const GeometryModel& model, const FacetMesh& boundary,
                         const BoundaryLayers& layers, const std::vector<std::int64_t>& fluid_tagged,
                         PointCloud& cloud) {
  const double dx = scene.geometry.spacing;
  for (std::size_t b = 0; b < scene.boundary_conditions.size(); ++b) {
    const BoundaryCondition& bc = scene.boundary_conditions[b];
    BoundaryInfo& info = cloud.boundaries[b];
    info.name = boundary_label(bc, b);
    info.type = to_string(bc.type);
    info.selector = bc.selector.fingerprint();
    info.depth = layer_depth(scene, bc);
    double measure = 0.0;
    for (std::size_t f : layers.selected[b]) measure += facet_measure(boundary, f);
    info.area = scene.dimension == 2 ? measure * cloud.thickness : measure;
    if (info.point_count > 0 || layers.shares[b]) continue;
    if (is_fluid(bc.type) && fluid_tagged[b + 1] > 0)
      throw InputError(scene_context(scene, bc, b) + ": the " +
                       (bc.type == BoundaryType::pore_pressure
                            ? std::string("drained layer of ") + bc.selector.describe() +
                                  " lies wholly in the layers of kinematic conditions (to drain a kinematic "
                                  "layer, select its boundary exactly as its condition does)"
                            : std::string("points within the depth of ") + bc.selector.describe() +
                                  " are all loaded by traction or pressure conditions (to feed a loaded boundary, "
                                  "select it exactly as its condition does)"));
    throw InputError(scene_context(scene, bc, b) + ": " + bc.selector.describe() + " of " + model.file +
                     " gets no lattice point (the selected boundary is too small "
                     "for dx = " +
                     std::to_string(dx) + " m)");
  }
}

// A lattice point exactly on a zero-width pre-crack loses every bond that touches the crack
// (precrack_crossing.hpp): almost certainly not what the user meant, so say so.
void warn_points_on_precracks(const PointCloud& cloud, const LatticeGrid& grid, const std::vector<std::uint8_t>& inside,
                              PreprocessReport& report) {
  if (cloud.precrack_vertices.empty()) return;
  const int d = cloud.dimension;
  FacetMesh cracks;
  cracks.dimension = d;
  for (std::size_t v = 0; v + 2 < cloud.precrack_vertices.size(); v += 3)
    cracks.vertices.push_back(
        {cloud.precrack_vertices[v], cloud.precrack_vertices[v + 1], cloud.precrack_vertices[v + 2]});
  for (std::size_t e = 0; e < cracks.vertices.size() / static_cast<std::size_t>(d); ++e) {
    std::int64_t corners[3] = {static_cast<std::int64_t>(e) * d, static_cast<std::int64_t>(e) * d + 1,
                               static_cast<std::int64_t>(e) * d + 2};
    cracks.add_facet(corners, 0);
  }
  LayerRequest on_crack;
  on_crack.boundary = 1;
  on_crack.depth = 0.0;  // assign_layers adds its 1e-9 dx slack
  for (std::size_t f = 0; f < cracks.facet_count(); ++f) on_crack.facets.push_back(f);
  const LayerTags touching = assign_layers(grid, inside, cracks, {on_crack}, true);
  std::int64_t count = 0;
  for (auto b : touching.boundary) count += b != 0;
  if (count > 0)
    report.warnings.push_back(std::to_string(count) +
                              " lattice point(s) lie exactly on a pre-crack and will lose every "
                              "bond that touches it; move the pre-crack between lattice rows");
}

// What mppm-solve will need (common/memory_estimate.hpp: the solver's arrays per point and
// per bond, one snapshot, the program), next to what this machine has available.
void estimate_solver_needs(const Scene& scene, const PointCloud& cloud, std::int64_t total, PreprocessReport& report) {
  report.lattice_neighbours = lattice_neighbour_count(scene.dimension, scene.geometry.horizon_factor);
  report.estimated_bonds = static_cast<double>(total) * static_cast<double>(report.lattice_neighbours);
  MemoryEstimateInput memory;
  memory.points = static_cast<std::uint64_t>(total);
  memory.bonds = static_cast<std::uint64_t>(report.estimated_bonds);
  memory.dimension = scene.dimension;
  memory.effects = scene.effects.names();
  memory.snapshot_fields = scene.output.fields;
  memory.damping = scene.numerics.damping != 0.0;
  memory.unsaturated = scene.material.pore_fluid && scene.material.pore_fluid->retention;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    memory.boundary_points += cloud.region[i] > 0 || cloud.boundary_id[i] > 0;
  report.estimated_memory_bytes = static_cast<double>(estimate_run_memory(memory).total_bytes);
  report.available_memory_bytes = available_memory_bytes();
}

}  // namespace

PreprocessResult preprocess(const Scene& scene, const PreprocessOptions& options) {
  const int d = scene.dimension;
  const double dx = scene.geometry.spacing;
  const double horizon = scene.geometry.horizon();
  if (!(dx > 0) || !(horizon >= dx))
    throw InputError(scene.path +
                     ": geometry.spacing and geometry.horizon_factor must give "
                     "dx > 0 and a horizon of at least dx");
  PreprocessResult result;
  PreprocessReport& report = result.report;
  auto clock = std::chrono::steady_clock::now();

  const GeometryRequest request = geometry_request(scene, options);
  const GeometryModel model = read_geometry(request);
  FacetMesh boundary = model.body_boundary();
  validate_and_orient_boundary(boundary, model.file);
  report.geometry_note = model.note;
  report.boundary_facets = boundary.facet_count();
  report.seconds_geometry = seconds_since(clock);
  const Box box = body_box(boundary, model, d, request.facet_size);
  report.body_low = box.low;
  report.body_high = box.high;
  check_body_wider_than_spacing(scene, model, box);

  // Selections first, so that a bad name is reported before the expensive work.
  const BoundaryLayers selections = select_boundaries(scene, model, boundary);
  PointCloud& cloud = result.cloud;
  cloud.dimension = d;
  cloud.spacing = dx;
  cloud.horizon = horizon;
  cloud.thickness = d == 2 ? scene.thickness : 1.0;
  cloud.precrack_vertices = precrack_vertices(scene, model);

  clock = std::chrono::steady_clock::now();
  const bool outside_layers = !selections.kinematic.empty() || !selections.drained.empty();
  const int padding = outside_layers ? static_cast<int>(std::ceil(horizon / dx - 1e-9)) + 1 : 0;
  const LatticeGrid grid = lattice_for_box(box.low, box.high, dx, d, padding);
  report.lattice = grid.count;
  const std::vector<std::uint8_t> inside = classify_inside(grid, boundary);
  report.seconds_inside = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  LayerTags layers = assign_layers(grid, inside, boundary, selections.kinematic, false);
  if (!selections.kinematic.empty()) drop_points_nearer_to_other_facets(layers, grid, boundary, horizon);
  std::vector<std::int64_t> fluid_tagged(scene.boundary_conditions.size() + 1, 0);
  if (!selections.drained.empty()) {
    LayerTags drained = assign_layers(grid, inside, boundary, selections.drained, false);
    drop_points_nearer_to_other_facets(drained, grid, boundary, horizon);
    fluid_tagged = add_where_free(layers, drained, scene.boundary_conditions.size());
  }
  LayerTags tractions = assign_layers(grid, inside, boundary, selections.loaded, true);
  if (!selections.fluxes.empty()) {
    const auto fed = add_where_free(tractions, assign_layers(grid, inside, boundary, selections.fluxes, true),
                                    scene.boundary_conditions.size());
    for (std::size_t k = 0; k < fed.size(); ++k) fluid_tagged[k] += fed[k];
  }
  report.seconds_layers = seconds_since(clock);

  const std::int64_t total = count_points_per_region(scene, model, inside, layers, report);
  place_points(cloud, grid, inside, layers, tractions, boundary, report.points_per_region, total);
  describe_boundaries(scene, model, boundary, selections, fluid_tagged, cloud);
  warn_points_on_precracks(cloud, grid, inside, report);
  estimate_solver_needs(scene, cloud, total, report);
  return result;
}

std::int64_t lattice_neighbour_count(int dimension, double horizon_factor) {
  return family_offset_count(dimension, horizon_factor);
}

std::string format_report(const Scene& scene, const PreprocessResult& result, const std::string& output_path) {
  const PointCloud& cloud = result.cloud;
  const PreprocessReport& r = result.report;
  const int d = cloud.dimension;
  std::ostringstream s;
  s << std::setprecision(6);
  s << "mppm-preprocess: " << scene.path << "\n";
  s << "  geometry     " << scene.geometry.file << " (" << d << "-D; " << r.boundary_facets
    << (d == 2 ? " boundary segments; " : " boundary triangles; ") << r.geometry_note << ")\n";
  s << "  lattice      dx = " << cloud.spacing << " m, horizon = " << cloud.horizon << " m (factor "
    << scene.geometry.horizon_factor << "), grid " << r.lattice[0] << " x " << r.lattice[1];
  if (d == 3) s << " x " << r.lattice[2];
  s << " cells incl. layer padding\n";
  s << "  bounding box [" << r.body_low[0] << ", " << r.body_high[0] << "] x [" << r.body_low[1] << ", "
    << r.body_high[1] << "]";
  if (d == 3) s << " x [" << r.body_low[2] << ", " << r.body_high[2] << "]";
  s << " m\n";
  std::int64_t total = 0;
  for (auto c : r.points_per_region) total += c;
  s << "  points       " << total << " in all; body (region 0): " << r.points_per_region[0] << "\n";
  for (std::size_t b = 0; b < cloud.boundaries.size(); ++b) {
    const BoundaryInfo& info = cloud.boundaries[b];
    s << "    [" << b + 1 << "] " << std::left << std::setw(12) << info.name << std::right << " " << std::setw(12)
      << info.type << ": ";
    const std::optional<std::size_t> shared = shared_boundary(cloud.boundaries, b);
    if (shared)
      s << "the " << (info.type == "pore_pressure" ? "layer" : "loaded points") << " of [" << *shared + 1 << "]";
    else if (info.type == "velocity" || info.type == "displacement")
      s << info.point_count << " layer points (region " << b + 1 << ")";
    else if (info.type == "pore_pressure")
      s << info.point_count << " drained layer points (region " << b + 1 << ")";
    else if (info.type == "fluid_flux")
      s << info.point_count << " fed body points (boundary_id " << b + 1 << ")";
    else
      s << info.point_count << " loaded body points (boundary_id " << b + 1 << ")";
    s << ", " << (d == 2 ? "length x thickness" : "area") << " " << info.area << " m^2\n";
  }
  if (!cloud.precrack_vertices.empty())
    s << "  pre-cracks   " << cloud.precrack_element_count() << (d == 2 ? " segments" : " triangles") << " from "
      << scene.geometry.precracks.size() << " selector(s)\n";
  s << "  bonds        ~" << std::setprecision(4) << r.estimated_bonds << " (" << total << " points x "
    << r.lattice_neighbours << " lattice neighbours within the horizon)\n";
  s << "  memory       ~" << format_bytes(r.estimated_memory_bytes) << " for mppm-solve (estimate)";
  if (r.available_memory_bytes)
    s << ", " << format_bytes(static_cast<double>(*r.available_memory_bytes)) << " available here";
  s << "\n";
  if (r.available_memory_bytes && r.estimated_memory_bytes > static_cast<double>(*r.available_memory_bytes))
    s << "  warning      the run needs more memory than this machine has available: mppm-solve will refuse it "
         "here; use a coarser geometry.spacing or fewer output.fields, or solve on a larger machine\n";
  s << "  time         geometry " << std::setprecision(3) << r.seconds_geometry << " s, inside test "
    << r.seconds_inside << " s, layers " << r.seconds_layers << " s\n";
  for (const std::string& warning : r.warnings) s << "  warning      " << warning << "\n";
  if (!output_path.empty()) s << "  wrote        " << output_path << "\n";
  return s.str();
}

}  // namespace mppm::pre
