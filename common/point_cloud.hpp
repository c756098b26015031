// The material points handed from the preprocessor to the solver (POINTS.vtp, docs/stages.md).
// Structure of arrays; positions in metres; 2-D clouds have z = 0.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mppm {

// region[i]: 0 = body, k > 0 = fictitious layer of boundary k (1-based index into
// `boundaries`, i.e. scene boundary condition k-1): a kinematic or a drained (pore_pressure) layer.
// boundary_id[i]: for a layer point, k (== region); for a body point inside the loaded
// depth of traction/pressure/fluid_flux boundary k, k (the nearest such boundary wins at corners;
// a fluid flux takes only points no traction or pressure has); otherwise 0.
struct BoundaryInfo {
  std::string name;   // scene label (physical group name, or "bc<k>")
  std::string type;   // "velocity", "displacement", "traction", "pressure", "pore_pressure", "fluid_flux"
  double area = 0.0;  // loaded area [m^2] (2-D: length * thickness)
  // Layer points (kinematic, pore_pressure) or loaded body points (traction, pressure, fluid_flux).
  // 0 for a fluid condition that shares the points of a mechanical condition with the same selector
  // (docs/stages.md "Boundaries"): a pore_pressure condition the layer of a kinematic one, a fluid_flux
  // condition the loaded points of a traction or pressure.
  std::int64_t point_count = 0;
  // What the layer was made from, so that the solver can refuse a scene that selects or sizes
  // it differently (the layers are fixed in the points file): the scene's selection
  // (Selector::fingerprint) and the layer depth [m] (horizon for kinematic layers, the loaded
  // depth for tractions). Empty / 0 when unknown (points files made before they were stored).
  std::string selector;
  double depth = 0.0;
};

struct PointCloud {
  int dimension = 2;
  double spacing = 0.0;    // dx [m]
  double horizon = 0.0;    // delta [m]
  double thickness = 1.0;  // 2-D thickness [m]
  std::vector<double> x, y, z;
  std::vector<double> volume;  // [m^3]
  std::vector<std::int32_t> region;
  std::vector<std::int32_t> boundary_id;
  // Outward unit normal of the boundary a loaded body point belongs to (boundary_id > 0 and
  // not a layer point); zero otherwise. Pressure acts along its negative.
  std::vector<double> normal_x, normal_y, normal_z;
  std::vector<BoundaryInfo> boundaries;
  // Pre-crack geometry [m]: 2-D segments (2 vertices each), 3-D triangles (3 vertices each),
  // flattened as x0 y0 z0 x1 y1 z1 (x2 y2 z2).
  std::vector<double> precrack_vertices;
  int precrack_vertices_per_element() const { return dimension == 2 ? 2 : 3; }
  std::size_t precrack_element_count() const {
    return precrack_vertices.size() / (3 * static_cast<std::size_t>(precrack_vertices_per_element()));
  }

  std::size_t size() const { return x.size(); }
  void resize(std::size_t n);
};

// The boundary whose points fluid boundary k shares (docs/stages.md "Boundaries"): for a
// pore_pressure boundary without layer points of its own, the kinematic (velocity, displacement)
// boundary with the same selector; for a fluid_flux boundary without loaded points of its own, the
// traction or pressure boundary with the same selector. None otherwise (a boundary with points of
// its own, not a fluid boundary, no selector stored, or no match).
std::optional<std::size_t> shared_boundary(const std::vector<BoundaryInfo>& boundaries, std::size_t k);

// Writes VTK XML PolyData (binary, appended, compressed), atomically (temporary + rename).
// Throws InputError if the file cannot be written.
void write_point_cloud(const PointCloud& cloud, const std::string& path);

// Reads and validates a points file; throws InputError naming the file and the problem
// (missing array, wrong size, non-positive volume, non-finite coordinate, ...).
PointCloud read_point_cloud(const std::string& path);

}  // namespace mppm
