// The geometry as the preprocessor sees it once gmsh has read and meshed it: the facets
// (2-D: segments, 3-D: triangles) of every entity of dimension d-1, in metres, tagged with their
// gmsh entity, plus the physical groups. Nothing here depends on gmsh, so the lattice, inside
// test and boundary-layer code can be tested on hand-made facets.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mppm::pre {

using Vec3 = std::array<double, 3>;

// Segments (dimension 2: 2 vertices each) or triangles (dimension 3: 3 vertices each).
struct FacetMesh {
  int dimension = 2;                 // of the body; a facet has `dimension` vertices
  std::vector<Vec3> vertices;        // [m]
  std::vector<std::int64_t> facets;  // vertex indices, `dimension` per facet
  std::vector<int> entity;           // gmsh entity tag of each facet

  std::size_t facet_count() const { return entity.size(); }
  const Vec3& vertex(std::size_t facet, int corner) const {
    return vertices[static_cast<std::size_t>(facets[facet * dimension + corner])];
  }
  void add_facet(const std::int64_t* corners, int entity_tag) {
    facets.insert(facets.end(), corners, corners + dimension);
    entity.push_back(entity_tag);
  }
};

struct PhysicalGroup {
  int dimension = 0;
  int tag = 0;
  std::string name;
  std::vector<int> entities;
};

struct GeometryModel {
  std::string file;  // for messages
  int dimension = 2;
  FacetMesh facets;                    // every entity of dimension d-1 (boundary, pre-cracks, ...)
  std::vector<int> boundary_entities;  // the d-1 entities that bound the body (sorted)
  std::vector<int> facet_entities;     // every d-1 entity (sorted)
  std::vector<PhysicalGroup> groups;   // every physical group, all dimensions
  std::string note;                    // what was done on reading (units, meshing), for the report
  // Bounding box of the body as the CAD kernel reports it [m] (OpenCASCADE pads it by its
  // tolerance, ~1e-7 of the size, evenly). Facet vertices of a curved boundary can miss the
  // extreme points, so the lattice prefers this box when it agrees with the facets (see
  // preprocessor.cpp). Empty when gmsh has none.
  bool has_cad_box = false;
  Vec3 cad_low{}, cad_high{};

  // The closed boundary of the body: the facets whose entity bounds the body.
  FacetMesh body_boundary() const;
  // Physical group names of dimension `dim` (sorted) and "name (dim D)" for every group.
  std::vector<std::string> group_names(int dim) const;
  std::string describe_groups() const;
};

// Reads a .geo .msh .step .stp .brep or .stl file through gmsh and meshes the entities of
// dimension d-1 with facets no longer than `facet_size` [m] (curvature-refined). gmsh meshes on
// one thread (its parallel meshing is not deterministic); the caller's OpenMP thread count is
// left as it was.
struct GeometryRequest {
  std::string file;
  int dimension = 2;
  double unit = 1.0;        // metres per file unit (.step/.stp carry their own unit)
  double facet_size = 0.0;  // [m]
  bool verbose = false;     // let gmsh talk
};

GeometryModel read_geometry(const GeometryRequest& request);

}  // namespace mppm::pre
