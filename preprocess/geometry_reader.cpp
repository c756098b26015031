// The only file that talks to gmsh: open a geometry file, find the body and its boundary
// entities, mesh the entities of dimension d-1 finely, and copy facets and physical groups
// out into a GeometryModel (metres). gmsh is a global singleton, so calls are serialized.
#include <gmsh.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <sstream>
#include <unordered_map>

#include "common/input_error.hpp"
#include "preprocess/geometry_model.hpp"

namespace mppm::pre {
namespace {

std::mutex gmsh_mutex;

// gmsh sets the caller's OpenMP thread count (omp_set_num_threads) from General.NumThreads,
// already in gmsh::initialize (to 1); this puts the caller's count back when the session ends,
// so the OpenMP loops after the read (inside test, layers) keep their threads.
class OmpThreadsRestorer {
 public:
  OmpThreadsRestorer() : threads_(omp_get_max_threads()) {}
  ~OmpThreadsRestorer() { omp_set_num_threads(threads_); }
  OmpThreadsRestorer(const OmpThreadsRestorer&) = delete;
  OmpThreadsRestorer& operator=(const OmpThreadsRestorer&) = delete;

 private:
  int threads_;
};

// gmsh::initialize / finalize for one read; finalize even when reading throws.
class GmshSession {
 public:
  explicit GmshSession(bool verbose) {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
    gmsh::option::setNumber("General.Verbosity", verbose ? 5 : 1);
    // gmsh works on one thread, whatever --threads says: its parallel curve and surface
    // meshing (gmsh 4.8, Mesh.MaxNumThreads1D/2D > 1) is not deterministic; on
    // notched_specimen_3d.step at 2 threads it gave a different boundary mesh (node positions,
    // at fine sizes even the triangle count) in about half of the runs, and so different layer
    // points (20732 vs 20734) and boundary areas. Results must not depend on the thread count
    // (preprocess/README.md); meshing on one thread takes 1.5-2x as long (figures there).
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::option::setNumber("Mesh.MaxNumThreads1D", 1);
    gmsh::option::setNumber("Mesh.MaxNumThreads2D", 1);
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // The first error gmsh logged since the last call (gmsh reports some problems without
  // throwing).
  std::string logged_error() {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string error;
    for (std::size_t i = seen_; i < log.size() && error.empty(); ++i)
      if (log[i].rfind("Error", 0) == 0) error = log[i];
    seen_ = log.size();
    return error;
  }

 private:
  std::size_t seen_ = 0;
};

std::string lower_extension(const std::string& file) {
  std::string ext = std::filesystem::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

struct VertexKeyHash {
  std::size_t operator()(const Vec3& v) const {
    std::size_t h = 1469598103934665603ull;
    for (double c : v) {
      std::uint64_t bits;
      static_assert(sizeof bits == sizeof c);
      std::memcpy(&bits, &c, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return h;
  }
};

std::vector<int> sorted_unique(std::vector<int> tags) {
  std::sort(tags.begin(), tags.end());
  tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
  return tags;
}

// The file's extension, lower case; throws if the file is missing or of an unknown format.
std::string checked_geometry_extension(const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file + ": geometry file not found");
  const std::string ext = lower_extension(file);
  static const std::set<std::string> known{".geo", ".msh", ".step", ".stp", ".brep", ".stl"};
  if (!known.count(ext))
    throw InputError(file + ": unsupported geometry format '" + ext + "' (expected .geo .msh .step .stp .brep .stl)");
  return ext;
}

// Copies the physical groups into the model; returns the body's entities (of dimension d): the
// physical groups of dimension d if there are any (gmsh's own convention for what a model
// contains), otherwise every entity of dimension d.
std::vector<int> read_groups_and_body(GeometryModel& model, int d) {
  gmsh::vectorpair higher;
  gmsh::model::getEntities(higher, d + 1 <= 3 ? d + 1 : 3);
  if (d == 2 && !higher.empty())
    throw InputError(model.file +
                     ": the scene is 2-D (dimension: 2) but the geometry has volumes "
                     "(expected planar surfaces in the xy plane)");
  gmsh::vectorpair body;
  gmsh::model::getEntities(body, d);
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  std::vector<int> body_tags;
  for (const auto& [gdim, gtag] : groups) {
    PhysicalGroup group;
    group.dimension = gdim;
    group.tag = gtag;
    gmsh::model::getPhysicalName(gdim, gtag, group.name);
    if (group.name.empty()) group.name = std::to_string(gtag);
    gmsh::model::getEntitiesForPhysicalGroup(gdim, gtag, group.entities);
    if (gdim == d) body_tags.insert(body_tags.end(), group.entities.begin(), group.entities.end());
    model.groups.push_back(group);
  }
  if (body_tags.empty())
    for (const auto& [edim, etag] : body) body_tags.push_back(etag);
  return sorted_unique(body_tags);
}

// The entities of dimension d-1 (model.facet_entities) and those that bound the body
// (model.boundary_entities).
void find_boundary_entities(GeometryModel& model, const std::vector<int>& body_tags, const std::string& ext) {
  const int d = model.dimension;
  const std::string& file = model.file;
  gmsh::vectorpair facet_entities;
  gmsh::model::getEntities(facet_entities, d - 1);
  for (const auto& [edim, etag] : facet_entities) model.facet_entities.push_back(etag);
  model.facet_entities = sorted_unique(model.facet_entities);

  if (!body_tags.empty()) {
    gmsh::vectorpair body_dimtags, boundary;
    for (int tag : body_tags) body_dimtags.push_back({d, tag});
    gmsh::model::getBoundary(body_dimtags, boundary, true, false, false);
    for (const auto& [bdim, btag] : boundary) model.boundary_entities.push_back(std::abs(btag));
  } else if (d == 3 && ext != ".stl" && ext != ".msh") {
    throw InputError(file +
                     ": the scene is 3-D (dimension: 3) but the geometry has no volume "
                     "(expected a solid; a 2-D geometry needs dimension: 2)");
  } else if (d == 3) {
    // A surface mesh without a volume (.stl, surface-only .msh): the surfaces are the
    // boundary; whether they close a volume is checked later.
    model.boundary_entities = model.facet_entities;
  } else {
    throw InputError(file + ": the geometry has no surface (a 2-D scene needs a planar surface)");
  }
  model.boundary_entities = sorted_unique(model.boundary_entities);
}

// The CAD bounding box of the body (or of its boundary, for a surface mesh), if gmsh knows it.
void read_cad_box(GeometryModel& model, const std::vector<int>& body_tags, double scale) {
  const int d = model.dimension;
  Vec3 low{HUGE_VAL, HUGE_VAL, HUGE_VAL}, high{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  const bool solid = !body_tags.empty();
  bool box_known = true;
  for (int tag : solid ? body_tags : model.boundary_entities) {
    double b[6];
    try {  // discrete entities (.msh, .stl) may have no box before their mesh is loaded
      gmsh::model::getBoundingBox(solid ? d : d - 1, tag, b[0], b[1], b[2], b[3], b[4], b[5]);
    } catch (...) {
      box_known = false;
      break;
    }
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], b[a] * scale);
      high[a] = std::max(high[a], b[a + 3] * scale);
    }
  }
  model.has_cad_box = box_known && std::isfinite(low[0]) && std::isfinite(high[0]) && low[0] <= high[0];
  model.cad_low = low;
  model.cad_high = high;
}

// Meshes the d-1 entities unless the file brought a mesh of them (.msh, .stl); says which in
// `note`.
void mesh_boundary_unless_meshed(GmshSession& session, const GeometryRequest& request, double scale,
                                 std::ostringstream& note) {
  const int d = request.dimension;
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, d - 1, -1);
  bool has_mesh = false;
  for (const auto& tags : element_tags) has_mesh = has_mesh || !tags.empty();
  session.logged_error();  // forget what the probing above may have logged
  if (!has_mesh) {
    const double size = request.facet_size / scale;  // in file units
    gmsh::option::setNumber("Mesh.MeshSizeMax", size);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    // Curved boundaries: at least 48 facets per full turn (area of the inscribed polygon within
    // 0.3 % of the circle) so that a curved part keeps its volume to well under 1 %.
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 48);
    gmsh::model::mesh::generate(d - 1);
    if (std::string error = session.logged_error(); !error.empty())
      throw InputError(request.file + ": gmsh could not mesh the boundary: " + error);
    note << "boundary meshed by gmsh with facets <= " << request.facet_size << " m";
  } else {
    note << "boundary mesh taken from the file";
  }
}

// Copies the nodes (all of them: facets may use nodes classified on lower-dimensional
// entities) into model.facets.vertices, merging duplicates; returns gmsh node tag -> vertex.
std::unordered_map<std::size_t, std::int64_t> copy_nodes(GeometryModel& model, double scale) {
  std::vector<std::size_t> all_node_tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(all_node_tags, coords, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, std::int64_t> node_index;
  std::unordered_map<Vec3, std::int64_t, VertexKeyHash> by_position;  // merges duplicates
  node_index.reserve(all_node_tags.size());
  for (std::size_t n = 0; n < all_node_tags.size(); ++n) {
    Vec3 p{coords[3 * n] * scale, coords[3 * n + 1] * scale, coords[3 * n + 2] * scale};
    auto [it, inserted] = by_position.emplace(p, static_cast<std::int64_t>(model.facets.vertices.size()));
    if (inserted) model.facets.vertices.push_back(p);
    node_index[all_node_tags[n]] = it->second;
  }
  return node_index;
}

// Copies the elements of the d-1 entities into model.facets (quadrangles as two triangles).
void copy_facets(GeometryModel& model, const std::unordered_map<std::size_t, std::int64_t>& node_index) {
  const int d = model.dimension;
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  for (int tag : model.facet_entities) {
    gmsh::model::mesh::getElements(types, element_tags, node_tags, d - 1, tag);
    for (std::size_t t = 0; t < types.size(); ++t) {
      std::string name;
      int edim = 0, order = 0, nodes = 0, primary = 0;
      std::vector<double> local;
      gmsh::model::mesh::getElementProperties(types[t], name, edim, order, nodes, local, primary);
      if (edim != d - 1) continue;
      const std::size_t count = element_tags[t].size();
      for (std::size_t e = 0; e < count; ++e) {
        std::int64_t c[4];
        for (int k = 0; k < std::min(primary, 4); ++k) {
          auto it = node_index.find(node_tags[t][e * nodes + k]);
          if (it == node_index.end()) throw InputError(model.file + ": element refers to a missing node");
          c[k] = it->second;
        }
        if (d == 2 && primary == 2) {
          model.facets.add_facet(c, tag);
        } else if (d == 3 && primary == 3) {
          model.facets.add_facet(c, tag);
        } else if (d == 3 && primary == 4) {  // quadrangle: two triangles
          const std::int64_t second[3] = {c[0], c[2], c[3]};
          model.facets.add_facet(c, tag);
          model.facets.add_facet(second, tag);
        } else {
          throw InputError(model.file + ": unsupported boundary element type '" + name + "'");
        }
      }
    }
  }
}

// A 2-D body must lie in a plane z = const; the lattice is built at z = 0.
void flatten_planar_body(GeometryModel& model) {
  double zmin = HUGE_VAL, zmax = -HUGE_VAL, size = 0.0;
  for (const Vec3& v : model.facets.vertices) {
    zmin = std::min(zmin, v[2]);
    zmax = std::max(zmax, v[2]);
    size = std::max({size, std::abs(v[0]), std::abs(v[1])});
  }
  if (zmax - zmin > 1e-9 * std::max(size, 1e-300))
    throw InputError(model.file + ": a 2-D scene needs a planar geometry in the xy plane (z spans " +
                     std::to_string(zmin) + " .. " + std::to_string(zmax) + " m)");
  for (Vec3& v : model.facets.vertices) v[2] = 0.0;
}

}  // namespace

FacetMesh GeometryModel::body_boundary() const {
  FacetMesh out;
  out.dimension = facets.dimension;
  out.vertices = facets.vertices;
  for (std::size_t f = 0; f < facets.facet_count(); ++f)
    if (std::binary_search(boundary_entities.begin(), boundary_entities.end(), facets.entity[f]))
      out.add_facet(&facets.facets[f * facets.dimension], facets.entity[f]);
  return out;
}

std::vector<std::string> GeometryModel::group_names(int dim) const {
  std::vector<std::string> names;
  for (const PhysicalGroup& g : groups)
    if (g.dimension == dim) names.push_back(g.name);
  std::sort(names.begin(), names.end());
  return names;
}

std::string GeometryModel::describe_groups() const {
  if (groups.empty()) return "none: the file defines no physical groups";
  std::ostringstream s;
  for (std::size_t i = 0; i < groups.size(); ++i) {
    static const char* kinds[] = {"point", "curve", "surface", "volume"};
    s << (i ? ", " : "") << "'" << groups[i].name << "' (" << kinds[std::clamp(groups[i].dimension, 0, 3)] << ")";
  }
  return s.str();
}

GeometryModel read_geometry(const GeometryRequest& request) {
  const std::string& file = request.file;
  const std::string ext = checked_geometry_extension(file);
  const int d = request.dimension;
  const bool step = ext == ".step" || ext == ".stp";
  // STEP files declare their length unit; let OpenCASCADE convert to metres directly.
  const double scale = step ? 1.0 : request.unit;

  std::lock_guard<std::mutex> lock(gmsh_mutex);
  const OmpThreadsRestorer omp_threads;  // declared before the session: restores after finalize
  GmshSession session(request.verbose);
  GeometryModel model;
  model.file = file;
  model.dimension = d;
  model.facets.dimension = d;
  std::ostringstream note;
  try {
    if (step) gmsh::option::setString("Geometry.OCCTargetUnit", "M");
    gmsh::open(file);
    if (std::string error = session.logged_error(); !error.empty())
      throw InputError(file + ": gmsh could not read the file: " + error);
    const std::vector<int> body_tags = read_groups_and_body(model, d);
    find_boundary_entities(model, body_tags, ext);
    read_cad_box(model, body_tags, scale);
    if (model.boundary_entities.empty())
      throw InputError(file + ": the geometry has no " + (d == 2 ? "surface" : "volume") +
                       " with a boundary (the scene is " + std::to_string(d) + "-D)");
    mesh_boundary_unless_meshed(session, request, scale, note);
    if (step) note << "; STEP length unit taken from the file";
    copy_facets(model, copy_nodes(model, scale));
  } catch (const InputError&) {
    throw;
  } catch (const std::string& message) {
    throw InputError(file + ": gmsh could not read or mesh the geometry: " + message);
  } catch (const std::exception& e) {
    throw InputError(file + ": gmsh could not read or mesh the geometry: " + e.what());
  }
  model.note = note.str();

  if (model.body_boundary().facet_count() == 0)
    throw InputError(file + ": the boundary of the body has no mesh elements (is the " +
                     (d == 2 ? "surface" : "volume") + " closed?)");
  if (d == 2) flatten_planar_body(model);
  return model;
}

}  // namespace mppm::pre
