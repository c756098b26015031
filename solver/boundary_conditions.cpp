// Boundary conditions: matching scene and points file, prescribed motion, surface loads,
// reactions.
#include "solver/boundary_conditions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "solver/compiled_effects.hpp"
#include "solver/exact_sum.hpp"

namespace mppm::solver {

namespace {

// The volume of a loaded or fed surface's points, summed exactly (the same bits for any partition).
double volume_sum(const std::vector<double>& volume, const std::vector<std::int32_t>& points) {
  ExactSum sum;
  for (const auto i : points) sum += volume[static_cast<std::size_t>(i)];
  return sum.value();
}

}  // namespace

double history_integral(const History& h, double t, std::size_t c) {
  if (h.times.empty() || t <= 0.0) return 0.0;
  auto value = [&](std::size_t k) { return h.values[k][c]; };
  double sum = 0.0;
  double a = 0.0;  // integrated up to a
  const std::size_t n = h.times.size();
  // Before the first row the value is the first row's.
  if (h.times.front() > 0.0) {
    const double b = std::min(t, h.times.front());
    sum += value(0) * (b - a);
    a = b;
  }
  for (std::size_t k = 0; k + 1 < n && a < t; ++k) {
    const double t0 = h.times[k], t1 = h.times[k + 1];
    if (t1 <= a || t1 <= t0) continue;
    const double lo = std::max(a, t0), hi = std::min(t, t1);
    if (hi <= lo) continue;
    auto at = [&](double s) { return value(k) + (value(k + 1) - value(k)) * (s - t0) / (t1 - t0); };
    sum += 0.5 * (at(lo) + at(hi)) * (hi - lo);  // exact for a linear piece
    a = hi;
  }
  if (a < t) sum += value(n - 1) * (t - a);
  return sum;
}

double history_slope(const History& h, double t, std::size_t c) {
  const std::size_t n = h.times.size();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double t0 = h.times[k], t1 = h.times[k + 1];
    if (t >= t0 && t < t1 && t1 > t0) return (h.values[k + 1][c] - h.values[k][c]) / (t1 - t0);
  }
  return 0.0;
}

BoundaryConditions::BoundaryConditions(const Scene& scene, const PointCloud& cloud, const PointData& p,
                                       const std::string& points_file) {
  dimension_ = p.dimension;
  match(scene, cloud, p.rotation_components, p.total(), p.region, p.boundary_id, p.volume, points_file);
}

BoundaryConditions::BoundaryConditions(const Scene& scene, const PointCloud& cloud, const std::string& points_file) {
  dimension_ = cloud.dimension;
  match(scene, cloud, scene.effects.micropolar ? rotation_components_of(cloud.dimension) : 0, cloud.size(),
        cloud.region, cloud.boundary_id, cloud.volume, points_file);
}

void BoundaryConditions::match(const Scene& scene, const PointCloud& cloud, int rotation_components, std::size_t points,
                               const std::vector<std::int32_t>& region, const std::vector<std::int32_t>& boundary_id,
                               const std::vector<double>& volume, const std::string& points_file) {
  rotation_components_ = rotation_components;
  condition_count_ = scene.boundary_conditions.size();
  prescribed_.assign(points, 0);
  if (cloud.boundaries.size() != condition_count_)
    throw InputError(points_file + ": holds " + std::to_string(cloud.boundaries.size()) +
                     " boundaries but the scene has " + std::to_string(condition_count_) +
                     " boundary conditions (rerun mppm-preprocess with this scene)");
  PointsByCondition by{std::vector<std::vector<std::int32_t>>(condition_count_ + 1),
                       std::vector<std::vector<std::int32_t>>(condition_count_ + 1)};
  for (std::size_t i = 0; i < points; ++i) {
    const auto r = region.empty() ? 0 : region[i];
    const auto b = boundary_id.empty() ? 0 : boundary_id[i];
    if (r < 0 || static_cast<std::size_t>(r) > condition_count_)
      throw InputError(points_file + ": point " + std::to_string(i) + " has region " + std::to_string(r) +
                       " but the scene has " + std::to_string(condition_count_) + " boundary conditions");
    if (r > 0)
      by.layer[r].push_back(static_cast<std::int32_t>(i));
    else if (b > 0 && static_cast<std::size_t>(b) <= condition_count_)
      by.loaded[b].push_back(static_cast<std::int32_t>(i));
  }
  for (std::size_t k = 0; k < condition_count_; ++k) {
    const BoundaryCondition& bc = scene.boundary_conditions[k];
    names_.push_back(bc.name);
    check_condition(scene, cloud, k, points_file);
    if (is_kinematic(bc.type))
      add_kinematic_layer(bc, k, by.layer[k + 1], points_file);
    else if (!is_fluid(bc.type))
      add_loaded_surface(bc, k, cloud, by.loaded[k + 1], volume, points_file);
  }
  // The fluid's conditions after the mechanical ones, whose points they may share.
  for (std::size_t k = 0; k < condition_count_; ++k) {
    const BoundaryType type = scene.boundary_conditions[k].type;
    if (type == BoundaryType::pore_pressure) add_drained_layer(scene, cloud, k, by, points_file);
    if (type == BoundaryType::fluid_flux) add_fed_surface(scene, cloud, k, by, volume, points_file);
  }
}

// Condition k against boundary k of the points file: its type, selection and loaded depth.
void BoundaryConditions::check_condition(const Scene& scene, const PointCloud& cloud, std::size_t k,
                                         const std::string& points_file) const {
  const BoundaryCondition& bc = scene.boundary_conditions[k];
  const BoundaryInfo& info = cloud.boundaries[k];
  if (info.type != to_string(bc.type))
    throw InputError(points_file + ": boundary " + std::to_string(k + 1) + " ('" + info.name + "') is of type '" +
                     info.type + "' but scene boundary condition '" + bc.name + "' is '" + to_string(bc.type) +
                     "' (rerun mppm-preprocess with this scene)");
  // The layers are fixed in the points file: a scene that selects or sizes them differently
  // would run silently with the old ones (e.g. --set boundary_conditions[0].depth=3mm).
  const std::string key =
      scene.path + ":" + std::to_string(bc.line) + ": boundary_conditions[" + std::to_string(k) + "]";
  if (!info.selector.empty() && info.selector != bc.selector.fingerprint())
    throw InputError(key + ": selects " + bc.selector.describe() + " but " + points_file + " was made with " +
                     info.selector + " for this boundary (rerun mppm-preprocess with this scene)");
  if (has_loaded_depth(bc.type) && info.depth > 0.0 &&
      std::abs(info.depth - bc.traction_depth) > 1e-9 * std::max(info.depth, bc.traction_depth)) {
    std::ostringstream s;
    s << key << ".depth: the loaded layer is " << bc.traction_depth << " m deep in the scene but " << points_file
      << " was made with " << info.depth
      << " m (the loaded points are fixed there: rerun mppm-preprocess with this scene)";
    throw InputError(s.str());
  }
}

void BoundaryConditions::add_kinematic_layer(const BoundaryCondition& bc, std::size_t k,
                                             std::vector<std::int32_t> points, const std::string& points_file) {
  const int D = dimension_;
  const int R = rotation_components_;
  if (points.empty())
    throw InputError(points_file + ": kinematic boundary condition '" + bc.name + "' has no layer points (region " +
                     std::to_string(k + 1) + ")");
  KinematicLayer layer;
  layer.condition = k;
  layer.name = bc.name;
  layer.points = std::move(points);
  layer.constrained.assign(D, 1);
  for (int c = 0; c < D && c < static_cast<int>(bc.constrained.size()); ++c)
    layer.constrained[c] = bc.constrained[c] ? 1 : 0;
  layer.displacement_type = bc.type == BoundaryType::displacement;
  layer.value = bc.value;
  if (bc.rotation && R > 0) layer.rotation = bc.rotation;
  for (auto i : layer.points) {
    std::uint8_t bits = 0;
    for (int c = 0; c < D; ++c)
      if (layer.constrained[c]) bits |= static_cast<std::uint8_t>(1u << c);
    if (layer.rotation)
      for (int c = 0; c < R; ++c) bits |= static_cast<std::uint8_t>(1u << (kRotationBit + c));
    prescribed_[i] = bits;
  }
  layers_.push_back(std::move(layer));
}

void BoundaryConditions::add_loaded_surface(const BoundaryCondition& bc, std::size_t k, const PointCloud& cloud,
                                            std::vector<std::int32_t> points, const std::vector<double>& volume,
                                            const std::string& points_file) {
  const int D = dimension_;
  LoadedSurface s;
  s.condition = k;
  s.name = bc.name;
  s.points = std::move(points);
  s.pressure = bc.type == BoundaryType::pressure;
  if (s.pressure) {
    s.normal.assign(s.points.size() * static_cast<std::size_t>(D), 0.0);
    const std::vector<double>* components[3] = {&cloud.normal_x, &cloud.normal_y, &cloud.normal_z};
    for (std::size_t q = 0; q < s.points.size(); ++q)
      for (int c = 0; c < D; ++c)
        if (!components[c]->empty()) s.normal[q * D + c] = (*components[c])[static_cast<std::size_t>(s.points[q])];
  }
  s.value = bc.value;
  s.area = cloud.boundaries[k].area;
  s.volume_sum = volume_sum(volume, s.points);
  if (s.points.empty() || !(s.volume_sum > 0.0) || !(s.area > 0.0))
    throw InputError(points_file + ": loaded boundary '" + bc.name + "' has no loaded points or no area (boundary_id " +
                     std::to_string(k + 1) + ")");
  surfaces_.push_back(std::move(s));
}

// The layer of drained condition k: its own (region k + 1: an inert layer, held still), or the
// layer of the kinematic condition with its selection (docs/stages.md "Boundaries").
void BoundaryConditions::add_drained_layer(const Scene& scene, const PointCloud& cloud, std::size_t k,
                                           const PointsByCondition& by, const std::string& points_file) {
  const BoundaryCondition& bc = scene.boundary_conditions[k];
  DrainedLayer layer;
  layer.condition = k;
  layer.name = bc.name;
  layer.value = bc.value;
  if (!by.layer[k + 1].empty()) {
    layer.points = by.layer[k + 1];
    const auto all = static_cast<std::uint8_t>((1u << dimension_) - 1u) |
                     static_cast<std::uint8_t>(((1u << rotation_components_) - 1u) << kRotationBit);
    for (const std::int32_t i : layer.points) prescribed_[static_cast<std::size_t>(i)] = all;
  } else if (const auto shared = shared_boundary(cloud.boundaries, k)) {
    layer.points = by.layer[*shared + 1];
    layer.inert = false;
  }
  if (layer.points.empty())
    throw InputError(scene.path + ":" + std::to_string(bc.line) + ": boundary_conditions[" + std::to_string(k) +
                     "] ('" + bc.name + "'): a drained boundary on a point set with no layer: " + points_file +
                     " has no layer points for it (region " + std::to_string(k + 1) +
                     ") and no kinematic boundary selected as it is to share (rerun mppm-preprocess with this scene)");
  drained_.push_back(std::move(layer));
}

// The fed points of flux condition k: its own (boundary_id k + 1), or the loaded points of the
// traction or pressure with its selection.
void BoundaryConditions::add_fed_surface(const Scene& scene, const PointCloud& cloud, std::size_t k,
                                         const PointsByCondition& by, const std::vector<double>& volume,
                                         const std::string& points_file) {
  const BoundaryCondition& bc = scene.boundary_conditions[k];
  FedSurface s;
  s.condition = k;
  s.name = bc.name;
  s.value = bc.value;
  s.area = cloud.boundaries[k].area;
  s.points = by.loaded[k + 1];
  if (s.points.empty())
    if (const auto shared = shared_boundary(cloud.boundaries, k)) s.points = by.loaded[*shared + 1];
  s.volume_sum = volume_sum(volume, s.points);
  if (s.points.empty() || !(s.volume_sum > 0.0) || !(s.area > 0.0))
    throw InputError(scene.path + ":" + std::to_string(bc.line) + ": boundary_conditions[" + std::to_string(k) +
                     "] ('" + bc.name + "'): a fluid-flux boundary with no fed points or no area in " + points_file +
                     " (boundary_id " + std::to_string(k + 1) + "; rerun mppm-preprocess with this scene)");
  fed_.push_back(std::move(s));
}

FluidBoundaryLayout BoundaryConditions::fluid_layout() const {
  FluidBoundaryLayout layout;
  for (const DrainedLayer& layer : drained_) {
    layout.drained.push_back({layer.points, layer.inert});
    if (layer.inert) layout.fluid_only_ids.push_back(static_cast<std::int32_t>(layer.condition + 1));
  }
  for (const FedSurface& s : fed_) layout.fluid_only_ids.push_back(static_cast<std::int32_t>(s.condition + 1));
  return layout;
}

void BoundaryConditions::prescribe(PointData& p, double t) const {
  const int D = dimension_;
  const int R = rotation_components_;
  for (const KinematicLayer& layer : layers_) {
    double u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    for (int c = 0; c < D; ++c) {
      if (!layer.constrained[c]) continue;
      if (layer.displacement_type) {
        u[c] = layer.value.component_at(t, c);
        v[c] = history_slope(layer.value, t, c);
      } else {
        u[c] = history_integral(layer.value, t, c);
        v[c] = layer.value.component_at(t, c);
      }
    }
    double w[3] = {0, 0, 0}, s[3] = {0, 0, 0};
    if (layer.rotation)
      for (int c = 0; c < R; ++c) {
        if (layer.displacement_type) {
          w[c] = layer.rotation->component_at(t, c);
          s[c] = history_slope(*layer.rotation, t, c);
        } else {
          w[c] = history_integral(*layer.rotation, t, c);
          s[c] = layer.rotation->component_at(t, c);
        }
      }
    for (auto i : layer.points) {
      for (int c = 0; c < D; ++c)
        if (layer.constrained[c]) {
          p.displacement[i * D + c] = u[c];
          p.velocity[i * D + c] = v[c];
        }
      if (layer.rotation)
        for (int c = 0; c < R; ++c) {
          p.rotation[i * R + c] = w[c];
          p.spin[i * R + c] = s[c];
        }
    }
  }
  // The inert drained layers take no part in the mechanics: held where they are.
  for (const DrainedLayer& layer : drained_) {
    if (!layer.inert) continue;
    for (const std::int32_t point : layer.points) {
      const auto i = static_cast<std::size_t>(point);
      for (int c = 0; c < D; ++c) p.displacement[i * D + c] = p.velocity[i * D + c] = 0.0;
      for (int c = 0; c < R; ++c) p.rotation[i * R + c] = p.spin[i * R + c] = 0.0;
    }
  }
}

void BoundaryConditions::prescribe_pore_pressure(PointData& p, double t) const {
  for (const DrainedLayer& layer : drained_) {
    const double pressure = layer.value.component_at(t, 0);
    for (const std::int32_t i : layer.points) p.pore_pressure[static_cast<std::size_t>(i)] = pressure;
  }
}

void BoundaryConditions::add_surface_loads(const PointData&, double t, std::vector<double>& b,
                                           const std::vector<std::int32_t>* rows) const {
  const int D = dimension_;
  std::size_t loaded = 0;  // the loaded point's position in the points of all surfaces
  for (const LoadedSurface& s : surfaces_) {
    const double scale = s.area / s.volume_sum;
    double tbar[3] = {0, 0, 0};
    const double pressure = s.pressure ? s.value.component_at(t, 0) : 0.0;
    if (!s.pressure)
      for (int c = 0; c < D; ++c) tbar[c] = s.value.component_at(t, c);
    for (std::size_t k = 0; k < s.points.size(); ++k, ++loaded) {
      const auto row = static_cast<std::size_t>(rows ? (*rows)[loaded] : s.points[k]);
      if (s.pressure)
        for (int c = 0; c < D; ++c) b[row * D + c] -= pressure * scale * s.normal[k * D + c];
      else
        for (int c = 0; c < D; ++c) b[row * D + c] += tbar[c] * scale;
    }
  }
}

namespace {

// The sums of one condition's load.csv entries: the volume of its points, their volume-weighted
// displacement, and its force.
struct LoadSums {
  ExactSum volume;
  std::array<ExactSum, 3> moment, force;
  bool has_force = false;  // else the force is the applied traction times the area
};

void add_displacement_moment(const PointData& p, const std::vector<std::int32_t>& points, LoadSums& s) {
  const int D = p.dimension;
  for (const auto i : points) {
    s.volume += p.volume[i];
    for (int c = 0; c < D; ++c) s.moment[c] += p.volume[i] * p.displacement[i * D + c];
  }
}

}  // namespace

std::vector<BoundaryConditions::LoadValues> BoundaryConditions::load_values(const PointData& p, double t) const {
  const int D = dimension_;
  // Exact sums (exact_sum.hpp), over all processes in a distributed run: the same bits however the
  // points are split.
  std::vector<LoadSums> sums(condition_count_);
  for (const KinematicLayer& layer : layers_) {
    LoadSums& s = sums[layer.condition];
    add_displacement_moment(p, layer.points, s);
    s.has_force = true;
    for (auto i : layer.points)
      for (int c = 0; c < D; ++c)
        if (layer.constrained[c]) s.force[c] -= p.force[i * D + c] * p.volume[i];
  }
  for (const LoadedSurface& surface : surfaces_) {
    LoadSums& s = sums[surface.condition];
    add_displacement_moment(p, surface.points, s);
    if (!surface.pressure) continue;
    s.has_force = true;
    const double pressure = surface.value.component_at(t, 0);
    const double scale = surface.area / surface.volume_sum;
    for (std::size_t k = 0; k < surface.points.size(); ++k) {
      const auto i = static_cast<std::size_t>(surface.points[k]);
      for (int c = 0; c < D; ++c) s.force[c] -= pressure * scale * surface.normal[k * D + c] * p.volume[i];
    }
  }
  std::vector<ExactSum> flat;
  for (const LoadSums& s : sums) {
    flat.push_back(s.volume);
    flat.insert(flat.end(), s.moment.begin(), s.moment.end());
    flat.insert(flat.end(), s.force.begin(), s.force.end());
  }
  std::vector<double> value(flat.size());
  if (p.processes)
    value = p.processes->sum(flat);
  else
    for (std::size_t k = 0; k < flat.size(); ++k) value[k] = flat[k].value();
  std::vector<LoadValues> out(condition_count_);
  for (std::size_t k = 0; k < condition_count_; ++k) {
    const double* v = &value[k * 7];  // volume, moment (3), force (3)
    out[k].name = names_[k];
    out[k].displacement.assign(D, 0.0);
    out[k].force.assign(D, 0.0);
    if (v[0] > 0.0)
      for (int c = 0; c < D; ++c) out[k].displacement[c] = v[1 + c] / v[0];
    for (int c = 0; c < D; ++c) out[k].force[c] = sums[k].has_force ? v[4 + c] : 0.0;
  }
  for (const LoadedSurface& surface : surfaces_)
    if (!surface.pressure)
      for (int c = 0; c < D; ++c) out[surface.condition].force[c] = surface.value.component_at(t, c) * surface.area;
  return out;
}

void BoundaryConditions::keep_owned(const LocalPoints& local) {
  if (!drained_.empty() || !fed_.empty())
    throw std::invalid_argument("the pore fluid's boundary conditions do not run across processes yet");
  const auto first = local.global_id.begin();
  const auto last = first + static_cast<std::ptrdiff_t>(local.owned);
  // The local index of global point g, or -1 when this process does not own it.
  auto local_index = [&](std::int32_t g) -> std::int32_t {
    const auto it = std::lower_bound(first, last, static_cast<std::int64_t>(g));
    return it != last && *it == g ? static_cast<std::int32_t>(it - first) : -1;
  };
  for (KinematicLayer& layer : layers_) {
    std::vector<std::int32_t> kept;
    for (const std::int32_t g : layer.points)
      if (const std::int32_t i = local_index(g); i >= 0) kept.push_back(i);
    layer.points = std::move(kept);
  }
  const auto D = static_cast<std::size_t>(dimension_);
  for (LoadedSurface& s : surfaces_) {
    std::vector<std::int32_t> kept;
    std::vector<double> normal;
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      const std::int32_t i = local_index(s.points[k]);
      if (i < 0) continue;
      kept.push_back(i);
      if (s.pressure)
        normal.insert(normal.end(), s.normal.begin() + static_cast<std::ptrdiff_t>(k * D),
                      s.normal.begin() + static_cast<std::ptrdiff_t>((k + 1) * D));
    }
    s.points = std::move(kept);
    s.normal = std::move(normal);
  }
  std::vector<std::uint8_t> prescribed(local.global_id.size(), 0);
  for (std::size_t k = 0; k < local.owned; ++k)
    prescribed[k] = prescribed_[static_cast<std::size_t>(local.global_id[k])];
  prescribed_ = std::move(prescribed);
}

}  // namespace mppm::solver
