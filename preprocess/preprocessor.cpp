// The preprocessing pipeline (see preprocessor.hpp): read and mesh, validate and orient the
// boundary, classify the lattice, add the layers, tag loaded points, collect pre-cracks.
#include "preprocess/preprocessor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "common/input_error.hpp"
#include "common/memory_estimate.hpp"
#include "common/progress.hpp"  // format_bytes
#include "preprocess/boundary_layers.hpp"
#include "preprocess/boundary_selection.hpp"
#include "preprocess/boundary_validation.hpp"
#include "preprocess/geometry_model.hpp"
#include "preprocess/inside_test.hpp"
#include "preprocess/lattice.hpp"

namespace mppm::pre {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string scene_context(const Scene& scene, const BoundaryCondition& bc, std::size_t index) {
  return scene.path + ":" + std::to_string(bc.line) + ": boundary_conditions[" +
         std::to_string(index) + "]";
}

std::string boundary_label(const BoundaryCondition& bc, std::size_t index) {
  if (!bc.name.empty()) return bc.name;
  if (!bc.selector.physical_group.empty()) return bc.selector.physical_group;
  return "bc" + std::to_string(index + 1);
}

}  // namespace

std::int64_t lattice_neighbour_count(int dimension, double horizon_factor) {
  const auto reach = static_cast<std::int64_t>(std::floor(horizon_factor + 1e-9));
  const double limit = (horizon_factor + 1e-9) * (horizon_factor + 1e-9);
  std::int64_t count = 0;
  const std::int64_t kz = dimension == 3 ? reach : 0;
  for (std::int64_t k = -kz; k <= kz; ++k)
    for (std::int64_t j = -reach; j <= reach; ++j)
      for (std::int64_t i = -reach; i <= reach; ++i)
        if ((i || j || k) && static_cast<double>(i * i + j * j + k * k) <= limit) ++count;
  return count;
}

PreprocessResult preprocess(const Scene& scene, const PreprocessOptions& options) {
  const int d = scene.dimension;
  const double dx = scene.geometry.spacing;
  const double horizon = scene.geometry.horizon();
  if (!(dx > 0) || !(horizon >= dx))
    throw InputError(scene.path + ": geometry.spacing and geometry.horizon_factor must give "
                                  "dx > 0 and a horizon of at least dx");
  PreprocessResult result;
  PreprocessReport& report = result.report;
  auto clock = std::chrono::steady_clock::now();

  GeometryRequest request;
  request.file = scene.geometry.file;
  request.dimension = d;
  request.unit = scene.geometry.unit;
  const double factor = options.facet_size_factor > 0 ? options.facet_size_factor : (d == 2 ? 0.25 : 3.0);
  request.facet_size = factor * dx;
  request.verbose = options.verbose;
  const GeometryModel model = read_geometry(request);
  FacetMesh boundary = model.body_boundary();
  validate_and_orient_boundary(boundary, model.file);
  report.geometry_note = model.note;
  report.boundary_facets = boundary.facet_count();
  report.seconds_geometry = seconds_since(clock);

  // Bounding box of the body from the boundary vertices (exact file coordinates; CAD bounding
  // boxes are padded by the kernel's tolerance).
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
               low[a] - model.cad_low[a] <= request.facet_size &&
               model.cad_high[a] - high[a] <= request.facet_size;
    if (agrees)
      for (int a = 0; a < d; ++a) {
        low[a] = model.cad_low[a];
        high[a] = model.cad_high[a];
      }
  }
  report.body_low = low;
  report.body_high = high;
  static const char* axes = "xyz";
  for (int a = 0; a < d; ++a)
    if (high[a] - low[a] < dx) {
      std::ostringstream s;
      s << scene.path << ": geometry.spacing (dx = " << dx << " m) is larger than the body "
        << model.file << " (extent " << high[a] - low[a] << " m along " << axes[a]
        << "): choose dx smaller than the body";
      throw InputError(s.str());
    }

  // Selections first, so that a bad name is reported before the expensive work.
  std::vector<LayerRequest> kinematic, loaded;
  std::vector<std::vector<std::size_t>> selected(scene.boundary_conditions.size());
  for (std::size_t b = 0; b < scene.boundary_conditions.size(); ++b) {
    const BoundaryCondition& bc = scene.boundary_conditions[b];
    selected[b] = select_boundary_facets(bc.selector, model, boundary, scene_context(scene, bc, b));
    LayerRequest layer;
    layer.boundary = static_cast<std::int32_t>(b + 1);
    layer.facets = selected[b];
    if (is_kinematic(bc.type)) {
      layer.depth = horizon;
      kinematic.push_back(layer);
    } else {
      layer.depth = bc.traction_depth > 0 ? bc.traction_depth : dx;
      loaded.push_back(layer);
    }
  }
  PointCloud& cloud = result.cloud;
  cloud.dimension = d;
  cloud.spacing = dx;
  cloud.horizon = horizon;
  cloud.thickness = d == 2 ? scene.thickness : 1.0;
  for (std::size_t p = 0; p < scene.geometry.precracks.size(); ++p) {
    const std::vector<double> v = select_precrack_vertices(
        scene.geometry.precracks[p], model,
        scene.path + ": geometry.precracks[" + std::to_string(p) + "]");
    cloud.precrack_vertices.insert(cloud.precrack_vertices.end(), v.begin(), v.end());
  }

  clock = std::chrono::steady_clock::now();
  const int padding = kinematic.empty() ? 0 : static_cast<int>(std::ceil(horizon / dx - 1e-9)) + 1;
  const LatticeGrid grid = lattice_for_box(low, high, dx, d, padding);
  report.lattice = grid.count;
  const std::vector<std::uint8_t> inside = classify_inside(grid, boundary);
  report.seconds_inside = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  LayerTags layers = assign_layers(grid, inside, boundary, kinematic, false);
  if (!kinematic.empty()) drop_points_nearer_to_other_facets(layers, grid, boundary, horizon);
  const LayerTags tractions = assign_layers(grid, inside, boundary, loaded, true);
  report.seconds_layers = seconds_since(clock);

  // Body points first (lattice order), then each layer k in turn: the solver finds the body
  // as a prefix and every layer as a contiguous block.
  const std::size_t nb = scene.boundary_conditions.size();
  report.points_per_region.assign(nb + 1, 0);
  for (std::size_t g = 0; g < inside.size(); ++g) {
    if (inside[g]) ++report.points_per_region[0];
    else if (layers.boundary[g] > 0) ++report.points_per_region[static_cast<std::size_t>(layers.boundary[g])];
  }
  if (report.points_per_region[0] == 0)
    throw InputError(scene.path + ": no lattice point falls inside the body of " + model.file +
                     " (dx = " + std::to_string(dx) + " m is too coarse for it)");
  std::int64_t total = 0;
  for (auto c : report.points_per_region) total += c;
  cloud.resize(static_cast<std::size_t>(total));
  const double volume = d == 2 ? dx * dx * cloud.thickness : dx * dx * dx;
  std::vector<std::int64_t> next(nb + 1, 0);
  for (std::size_t r = 1; r <= nb; ++r) next[r] = next[r - 1] + report.points_per_region[r - 1];
  cloud.boundaries.resize(nb);
  for (std::size_t g = 0; g < inside.size(); ++g) {
    const std::int32_t region = inside[g] ? 0 : layers.boundary[g];
    if (!inside[g] && region == 0) continue;
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
  for (std::size_t b = 0; b < nb; ++b) {
    const BoundaryCondition& bc = scene.boundary_conditions[b];
    BoundaryInfo& info = cloud.boundaries[b];
    info.name = boundary_label(bc, b);
    info.type = to_string(bc.type);
    info.selector = bc.selector.fingerprint();
    info.depth = is_kinematic(bc.type) ? horizon : (bc.traction_depth > 0 ? bc.traction_depth : dx);
    double measure = 0.0;
    for (std::size_t f : selected[b]) measure += facet_measure(boundary, f);
    info.area = d == 2 ? measure * cloud.thickness : measure;
    if (info.point_count == 0)
      throw InputError(scene_context(scene, bc, b) + ": " + bc.selector.describe() + " of " +
                       model.file + " gets no lattice point (the selected boundary is too small "
                       "for dx = " + std::to_string(dx) + " m)");
  }

  // A lattice point exactly on a zero-width pre-crack loses every bond that touches the crack
  // (precrack_crossing.hpp): almost certainly not what the user meant, so say so.
  if (!cloud.precrack_vertices.empty()) {
    FacetMesh cracks;
    cracks.dimension = d;
    for (std::size_t v = 0; v + 2 < cloud.precrack_vertices.size(); v += 3)
      cracks.vertices.push_back({cloud.precrack_vertices[v], cloud.precrack_vertices[v + 1],
                                 cloud.precrack_vertices[v + 2]});
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

  report.lattice_neighbours = lattice_neighbour_count(d, scene.geometry.horizon_factor);
  report.estimated_bonds = static_cast<double>(total) * static_cast<double>(report.lattice_neighbours);
  // What mppm-solve will need (common/memory_estimate.hpp: the solver's arrays per point and
  // per bond, one snapshot, the program), next to what this machine has available.
  MemoryEstimateInput memory;
  memory.points = static_cast<std::uint64_t>(total);
  memory.bonds = static_cast<std::uint64_t>(report.estimated_bonds);
  memory.dimension = d;
  memory.effects = scene.effects.names();
  memory.snapshot_fields = scene.output.fields;
  memory.damping = scene.numerics.damping != 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) memory.boundary_points += cloud.region[i] > 0 || cloud.boundary_id[i] > 0;
  report.estimated_memory_bytes = static_cast<double>(estimate_run_memory(memory).total_bytes);
  report.available_memory_bytes = available_memory_bytes();
  return result;
}

std::string format_report(const Scene& scene, const PreprocessResult& result,
                          const std::string& output_path) {
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
  s << "  bounding box [" << r.body_low[0] << ", " << r.body_high[0] << "] x [" << r.body_low[1]
    << ", " << r.body_high[1] << "]";
  if (d == 3) s << " x [" << r.body_low[2] << ", " << r.body_high[2] << "]";
  s << " m\n";
  std::int64_t total = 0;
  for (auto c : r.points_per_region) total += c;
  s << "  points       " << total << " in all; body (region 0): " << r.points_per_region[0] << "\n";
  for (std::size_t b = 0; b < cloud.boundaries.size(); ++b) {
    const BoundaryInfo& info = cloud.boundaries[b];
    s << "    [" << b + 1 << "] " << std::left << std::setw(12) << info.name << std::right << " "
      << std::setw(12) << info.type << ": ";
    if (info.type == "velocity" || info.type == "displacement")
      s << info.point_count << " layer points (region " << b + 1 << ")";
    else
      s << info.point_count << " loaded body points (boundary_id " << b + 1 << ")";
    s << ", " << (d == 2 ? "length x thickness" : "area") << " " << info.area << " m^2\n";
  }
  if (!cloud.precrack_vertices.empty())
    s << "  pre-cracks   " << cloud.precrack_element_count() << (d == 2 ? " segments" : " triangles")
      << " from " << scene.geometry.precracks.size() << " selector(s)\n";
  s << "  bonds        ~" << std::setprecision(4) << r.estimated_bonds << " (" << total << " points x "
    << r.lattice_neighbours << " lattice neighbours within the horizon)\n";
  s << "  memory       ~" << format_bytes(r.estimated_memory_bytes) << " for mppm-solve (estimate)";
  if (r.available_memory_bytes) s << ", " << format_bytes(static_cast<double>(*r.available_memory_bytes)) << " available here";
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
