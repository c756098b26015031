// Construction of the solver's point storage from a point cloud.
#include "solver/point_data.hpp"

#include <algorithm>

#include "solver/compiled_effects.hpp"

namespace mppm::solver {

namespace {

// Dimension, counts, ids and positions of the cloud's points.
void set_geometry(PointData& p, const PointCloud& cloud, const EffectSet& effects) {
  const int D = cloud.dimension;
  const std::size_t n = cloud.size();
  p.dimension = D;
  p.rotation_components = effects.micropolar ? rotation_components_of(D) : 0;
  p.owned = n;
  p.ghost = 0;
  p.position = cloud_positions(cloud);
}

// The state arrays of the dimension and the effects, zero (an effect that is off allocates nothing).
void allocate_state(PointData& p, const EffectSet& effects);

// Frees v's memory (v = {} would keep its capacity).
template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

}  // namespace

std::vector<double> cloud_positions(const PointCloud& cloud) {
  const auto D = static_cast<std::size_t>(cloud.dimension);
  std::vector<double> x(cloud.size() * D);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double xyz[3] = {cloud.x[i], cloud.y[i], cloud.z.empty() ? 0.0 : cloud.z[i]};
    for (std::size_t c = 0; c < D; ++c) x[i * D + c] = xyz[c];
  }
  return x;
}

PointData make_point_data(const PointCloud& cloud, const EffectSet& effects) {
  PointData p;
  set_geometry(p, cloud, effects);
  const std::size_t n = p.owned;
  p.volume = cloud.volume;
  p.region = cloud.region.empty() ? std::vector<std::int32_t>(n, 0) : cloud.region;
  p.boundary_id = cloud.boundary_id.empty() ? std::vector<std::int32_t>(n, 0) : cloud.boundary_id;
  allocate_state(p, effects);
  return p;
}

PointData make_point_data(PointCloud&& cloud, const EffectSet& effects) {
  PointData p;
  set_geometry(p, cloud, effects);
  const std::size_t n = p.owned;
  for (auto* v : {&cloud.x, &cloud.y, &cloud.z, &cloud.normal_x, &cloud.normal_y, &cloud.normal_z}) release(*v);
  p.volume = std::move(cloud.volume);
  p.region = cloud.region.empty() ? std::vector<std::int32_t>(n, 0) : std::move(cloud.region);
  p.boundary_id = cloud.boundary_id.empty() ? std::vector<std::int32_t>(n, 0) : std::move(cloud.boundary_id);
  release(cloud.volume);
  release(cloud.region);
  release(cloud.boundary_id);
  allocate_state(p, effects);
  return p;
}

namespace {

void allocate_state(PointData& p, const EffectSet& effects) {
  const int D = p.dimension;
  const int R = p.rotation_components;
  const std::size_t n = p.owned;
  const std::size_t DD = static_cast<std::size_t>(D) * D;
  p.displacement.assign(n * D, 0.0);
  p.velocity.assign(n * D, 0.0);
  p.force.assign(n * D, 0.0);
  const std::size_t symmetric = static_cast<std::size_t>(D) * (D + 1) / 2;
  p.shape_inverse.assign(n * symmetric, 0.0);
  p.stabilization_ck.assign(n * symmetric, 0.0);
  p.detached.assign(n, 0);
  p.strain.assign(n * DD, 0.0);
  p.force_tensor.assign(n * DD, 0.0);
  p.stabilization_energy.assign(n, 0.0);
  if (R > 0) {
    p.rotation.assign(n * R, 0.0);
    p.spin.assign(n * R, 0.0);
    p.moment.assign(n * R, 0.0);
    p.stabilization_rot.assign(n, 0.0);
    p.wryness.assign(n * R * D, 0.0);
    p.moment_tensor.assign(n * R * D, 0.0);
  }
  if (effects.viscoplasticity) {
    p.plastic_strain.assign(n * 9, 0.0);
    if (R > 0) p.plastic_wryness.assign(n * R * D, 0.0);
    p.equivalent_plastic_strain.assign(n, 0.0);
    p.plastic_dissipation.assign(n, 0.0);
    p.plastic_active.assign(n, 1);  // narrowed to the region by build_model
  }
  if (effects.damage) {
    p.no_fail.assign(n, 0);
    p.bonds_broken.assign(n, 0);
    p.previous_displacement.assign(n * D, 0.0);
    p.force_tensor_sum.assign(n * DD, 0.0);
    if (R > 0) {
      p.previous_rotation.assign(n * R, 0.0);
      p.moment_tensor_sum.assign(n * R * D, 0.0);
    }
  }
  if (effects.pore_fluid) {  // set by start_fluid (solver/pore_fluid.hpp)
    p.pore_pressure.assign(n, 0.0);
    p.fluid_content_change.assign(n, 0.0);
    p.fluid_rate.assign(n, 0.0);
  }
}

}  // namespace

bool inside_box(const double* x, int dimension, const std::array<std::array<double, 3>, 2>& box) {
  for (int a = 0; a < dimension; ++a)
    if (x[a] < box[0][a] || x[a] > box[1][a]) return false;
  return true;
}

std::optional<std::size_t> owned_index(const PointData& p, std::size_t point) {
  if (p.global_id.empty()) return point;
  const auto owned_end = p.global_id.begin() + static_cast<std::ptrdiff_t>(p.owned);
  const auto at = std::lower_bound(p.global_id.begin(), owned_end, static_cast<std::int64_t>(point));
  if (at == owned_end || *at != static_cast<std::int64_t>(point)) return std::nullopt;
  return static_cast<std::size_t>(at - p.global_id.begin());
}

}  // namespace mppm::solver
