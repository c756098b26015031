// The preprocessing stage as a library call: scene -> geometry (gmsh) -> lattice points with
// boundary layers, loaded-boundary tags and pre-crack geometry (docs/scene.md, docs/theory.md section 8).
// mppm-preprocess is a thin main around it; tests call it directly.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"

namespace mppm::pre {

struct PreprocessOptions {
  bool verbose = false;  // let gmsh print its log
  // Boundary facet size / dx; 0 = default: 2-D 1/4, 3-D 3. Flat faces are exact at any facet
  // size; curved ones are refined by curvature (48 facets per turn) regardless, so 3-D facets
  // can be large, which keeps gmsh's surface meshing (the dominant cost) small.
  double facet_size_factor = 0;
};

struct PreprocessReport {
  std::string geometry_note;
  std::size_t boundary_facets = 0;
  std::array<std::int64_t, 3> lattice{1, 1, 1};   // cells of the padded grid
  std::array<double, 3> body_low{}, body_high{};  // bounding box of the body boundary [m]
  std::vector<std::int64_t> points_per_region;    // [0] = body, [k] = layer of boundary k
  std::int64_t lattice_neighbours = 0;            // lattice points within the horizon of a point
  double estimated_bonds = 0.0;
  double estimated_memory_bytes = 0.0;                  // of mppm-solve (common/memory_estimate.hpp)
  std::optional<std::uint64_t> available_memory_bytes;  // MemAvailable of this machine
  double seconds_geometry = 0.0, seconds_inside = 0.0, seconds_layers = 0.0;
  std::vector<std::string> warnings;  // printed with the report
};

struct PreprocessResult {
  PointCloud cloud;
  PreprocessReport report;
};

// Throws InputError (exit code 2) for bad geometry or selections, naming the file.
PreprocessResult preprocess(const Scene& scene, const PreprocessOptions& options = {});

// The one-screen summary printed by mppm-preprocess.
std::string format_report(const Scene& scene, const PreprocessResult& result, const std::string& output_path);

// Lattice points j != 0 with |j| dx <= horizon (1e-9 dx slack), for the bond estimate.
std::int64_t lattice_neighbour_count(int dimension, double horizon_factor);

}  // namespace mppm::pre
