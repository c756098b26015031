// Boundary conditions on the preprocessor's layers (docs/theory.md section 8): kinematic conditions
// (velocity / displacement, optional micro-rotation) prescribe the motion of the fictitious
// layer points of region k = condition k-1; tractions and pressures become a body force
// density b = t_bar A / sum V on the body points with boundary_id k. The pore fluid's
// (docs/theory.md section 12): a drained (pore_pressure) condition prescribes the pressure of its
// layer (its own, region k, or the kinematic layer it shares), a fluid flux becomes a source
// s = q A / sum V on its fed points (its own, boundary_id k, or the loaded points it shares).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "solver/fluid_boundaries.hpp"
#include "solver/local_points.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// Exact integral over [0, t] of component c of a piecewise-linear history held constant
// outside its table (velocity -> displacement of a layer).
double history_integral(const History& h, double t, std::size_t c);
// Slope of component c at t (displacement -> velocity of a layer); right derivative.
double history_slope(const History& h, double t, std::size_t c);

struct KinematicLayer {
  std::size_t condition = 0;  // index into Scene::boundary_conditions
  std::string name;
  std::vector<std::int32_t> points;
  std::vector<std::uint8_t> constrained;  // D flags
  bool displacement_type = false;         // else velocity
  History value;
  std::optional<History> rotation;  // rotation (displacement) or rotation rate (velocity)
};

struct LoadedSurface {
  std::size_t condition = 0;
  std::string name;
  std::vector<std::int32_t> points;
  bool pressure = false;
  // Pressure only: the outward unit normal of each point of `points` (D per point, in that order),
  // along whose negative the pressure acts. Kept here rather than per point of the model: only the
  // loaded points have one.
  std::vector<double> normal;
  History value;
  double area = 0.0;        // BoundaryInfo::area
  double volume_sum = 0.0;  // sum of V over the loaded points
};

// A drained boundary: its layer points carry the prescribed pressure p(t). Inert when the layer is
// its own (no kinematic condition moves it): its points then hold still and leave the mechanics
// (Model::inert_points).
struct DrainedLayer {
  std::size_t condition = 0;
  std::string name;
  std::vector<std::int32_t> points;
  History value;  // p(t) [Pa]
  bool inert = true;
};

// A fluid-flux boundary: inflow q(t) per area [m/s] through `area`, as the source
// s = q A / volume_sum [1/s] on its points.
struct FedSurface {
  std::size_t condition = 0;
  std::string name;
  std::vector<std::int32_t> points;
  History value;
  double area = 0.0;
  double volume_sum = 0.0;
};

class BoundaryConditions {
 public:
  // No conditions at all (a free body).
  explicit BoundaryConditions(const PointData& points)
      : dimension_(points.dimension),
        rotation_components_(points.rotation_components),
        prescribed_(points.total(), 0) {}
  // Matches the scene's conditions with the cloud's regions and boundary ids; throws
  // InputError naming the points file when they do not agree.
  BoundaryConditions(const Scene& scene, const PointCloud& cloud, const PointData& points,
                     const std::string& points_file);
  // The same from the cloud alone (its points are the model's, in order, all owned), so that the
  // conditions can be set up before the model takes over the cloud's arrays (mppm-solve).
  BoundaryConditions(const Scene& scene, const PointCloud& cloud, const std::string& points_file);

  // Sets the prescribed components of u, v (and w, spin) at time t; the inert drained layers' to 0.
  void prescribe(PointData& points, double t) const;
  // Pore fluid: sets the pressure of the drained layers' points to their p(t).
  void prescribe_pore_pressure(PointData& points, double t) const;
  // Body force density [N/m^3] of tractions and pressures at time t, added to `b` (D per point).
  // With `rows`, b has D values per row instead, and the k-th loaded point (the points of
  // surfaces() in order) adds to row rows[k].
  void add_surface_loads(const PointData& points, double t, std::vector<double>& b,
                         const std::vector<std::int32_t>* rows = nullptr) const;

  // The prescribed components of point i: bit c for displacement component c, bit
  // kRotationBit + c for rotation component c (0: none).
  std::uint8_t prescribed(std::size_t i) const { return prescribed_[i]; }
  static constexpr int kRotationBit = 3;
  bool prescribed_displacement(std::size_t i, int c) const { return (prescribed_[i] >> c) & 1; }
  bool prescribed_rotation(std::size_t i, int c) const { return (prescribed_[i] >> (kRotationBit + c)) & 1; }

  const std::vector<KinematicLayer>& layers() const { return layers_; }
  const std::vector<LoadedSurface>& surfaces() const { return surfaces_; }
  const std::vector<DrainedLayer>& drained() const { return drained_; }
  const std::vector<FedSurface>& fed() const { return fed_; }
  // What the model needs of the drained layers and the fluid's own boundary ids.
  FluidBoundaryLayout fluid_layout() const;
  // True when scene condition k is a drained (pore_pressure) one.
  bool drained_condition(std::size_t k) const {
    for (const DrainedLayer& layer : drained_)
      if (layer.condition == k) return true;
    return false;
  }

  // Per scene condition (scene order): mean displacement of its points and its force [N]:
  // kinematic: reaction = -sum_layer f V on the constrained components (the force the layer
  // transmits to the body; positive along the prescribed motion when the body resists);
  // traction/pressure: the applied force sum b V; pore fluid conditions: zero (their load.csv
  // columns are the fluid's volumes, ExplicitDynamics::fluid_boundary_flows).
  struct LoadValues {
    std::string name;
    std::vector<double> displacement;  // D
    std::vector<double> force;         // D
  };
  std::vector<LoadValues> load_values(const PointData& points, double t) const;

  std::size_t condition_count() const { return condition_count_; }

  // A distributed run's process (docs/theory.md section 13): the conditions matched against the
  // whole points file (their checks and loaded volumes are the whole model's) keep the points this
  // process owns, renumbered to its local indices. The pore fluid's conditions are refused
  // (std::invalid_argument).
  void keep_owned(const LocalPoints& local);

 private:
  // The points' rotation components R, count, region, boundary id and volume (empty region or
  // boundary id: all 0).
  void match(const Scene& scene, const PointCloud& cloud, int rotation_components, std::size_t points,
             const std::vector<std::int32_t>& region, const std::vector<std::int32_t>& boundary_id,
             const std::vector<double>& volume, const std::string& points_file);
  // The points of each condition k (at k + 1): of its layer, or loaded (or fed) body points.
  struct PointsByCondition {
    std::vector<std::vector<std::int32_t>> layer, loaded;
  };
  void check_condition(const Scene& scene, const PointCloud& cloud, std::size_t k,
                       const std::string& points_file) const;
  void add_kinematic_layer(const BoundaryCondition& bc, std::size_t k, std::vector<std::int32_t> points,
                           const std::string& points_file);
  void add_loaded_surface(const BoundaryCondition& bc, std::size_t k, const PointCloud& cloud,
                          std::vector<std::int32_t> points, const std::vector<double>& volume,
                          const std::string& points_file);
  void add_drained_layer(const Scene& scene, const PointCloud& cloud, std::size_t k, const PointsByCondition& points,
                         const std::string& points_file);
  void add_fed_surface(const Scene& scene, const PointCloud& cloud, std::size_t k, const PointsByCondition& points,
                       const std::vector<double>& volume, const std::string& points_file);
  int dimension_ = 2;
  int rotation_components_ = 0;
  std::size_t condition_count_ = 0;
  std::vector<std::string> names_;
  std::vector<KinematicLayer> layers_;
  std::vector<LoadedSurface> surfaces_;
  std::vector<DrainedLayer> drained_;
  std::vector<FedSurface> fed_;
  std::vector<std::uint8_t> prescribed_;  // one byte of component bits per point
};

}  // namespace mppm::solver
