// Construction of the solver's point storage from a point cloud.
#include "solver/point_data.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "solver/compiled_effects.hpp"
#include "solver/parallel_policy.hpp"

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
  const std::size_t symmetric = static_cast<std::size_t>(D) * (D + 1) / 2;
  std::vector<std::function<void()>> fills;
  const auto fill = [&fills](auto& array, std::size_t size, int value = 0) {
    fills.emplace_back([&array, size, value] { array.assign(size, value); });
  };
  for (auto* v : {&p.displacement, &p.velocity, &p.force}) fill(*v, n * D);
  fill(p.shape_inverse, n * symmetric);
  fill(p.stabilization_ck, n * symmetric);
  fill(p.detached, n);
  fill(p.strain, n * DD);
  fill(p.force_tensor, n * DD);
  fill(p.stabilization_energy, n);
  if (R > 0) {
    for (auto* v : {&p.rotation, &p.spin, &p.moment}) fill(*v, n * R);
    fill(p.stabilization_rot, n);
    fill(p.wryness, n * R * D);
    fill(p.moment_tensor, n * R * D);
  }
  if (effects.viscoplasticity) {
    fill(p.plastic_strain, n * 9);
    if (R > 0) fill(p.plastic_wryness, n * R * D);
    fill(p.equivalent_plastic_strain, n);
    fill(p.plastic_dissipation, n);
    fill(p.plastic_active, n, 1);  // narrowed to the region by build_model
  }
  if (effects.damage) {
    fill(p.no_fail, n);
    fill(p.bonds_broken, n);
    fill(p.previous_displacement, n * D);
    fill(p.force_tensor_sum, n * DD);
    if (R > 0) {
      fill(p.previous_rotation, n * R);
      fill(p.moment_tensor_sum, n * R * D);
    }
  }
  if (effects.pore_fluid)  // set by start_fluid (solver/pore_fluid.hpp)
    for (auto* v : {&p.pore_pressure, &p.fluid_content_change, &p.fluid_rate}) fill(*v, n);
  // The fills side by side on the threads: the arrays' first writes (page faults and zeroing, some
  // hundred MB in a large 3-D model) were the whole of this phase.
  run_tasks(fills);
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
