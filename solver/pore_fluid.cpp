// Flow of the pore fluid on the lattice (see pore_fluid.hpp; docs/theory.md section 12).
#include "solver/pore_fluid.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/lattice_offsets.hpp"
#include "solver/exact_point_sums.hpp"
#include "solver/flow_super_step.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/unsaturated_coupling.hpp"

namespace mppm::solver {

namespace {

// Body points carry the fluid; fictitious layer points (region > 0) none.
bool carries_fluid(const PointData& p, std::size_t i) { return p.region[i] == 0; }

// Visits the conducting bonds of body point i: acting, to a body point. visit(j, xi, |xi|).
template <int D, class Visit>
void for_each_conducting_bond(const PointData& p, const BondFamilies& f, std::size_t i, Visit&& visit) {
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    if (!f.acting(b)) continue;
    const auto j = static_cast<std::size_t>(f.neighbor[b]);
    if (!carries_fluid(p, j)) continue;
    double xi[D];
    bond_vector<D>(f, p.position.data(), i, b, xi);
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) r2 += xi[a] * xi[a];
    visit(j, xi, std::sqrt(r2));
  }
}

// Visits the conducting drain bonds of row `row` of the drain bonds (docs/theory.md section 12):
// visit(j, xi, |xi|, bond) with j the drained-layer point.
template <class Visit>
void for_each_drain_bond(const PointData& p, const BondFamilies& f, const DrainBonds& d, std::size_t row,
                         Visit&& visit) {
  for (auto b = static_cast<std::size_t>(d.offset[row]); b < static_cast<std::size_t>(d.offset[row + 1]); ++b) {
    if (!d.conducts(p, f, row, b)) continue;
    visit(static_cast<std::size_t>(d.neighbor[b]), &d.xi[3 * b], d.length[b], b);
  }
}

template <int D>
double potential(const PointData& p, const FluidConstants& fl, std::size_t i) {
  double gx = 0.0;
  for (int a = 0; a < D; ++a) gx += fl.gravity[a] * p.position[i * D + a];
  return p.pore_pressure[i] - fl.fluid_density * gx;
}

bool has_gravity(const FluidConstants& fl) {
  return fl.fluid_density != 0.0 && (fl.gravity[0] != 0.0 || fl.gravity[1] != 0.0 || fl.gravity[2] != 0.0);
}

// The bond conductivity's relative factor: (k_r,i + k_r,j) / 2 unsaturated (docs/theory.md section 12), else 1.
template <bool Unsaturated>
double relative_conductivity(const PointData& p, std::size_t i, std::size_t j) {
  if constexpr (Unsaturated)
    return 0.5 * (p.relative_permeability[i] + p.relative_permeability[j]);
  else
    return 1.0;
}

template <int D, bool Unsaturated>
void fluid_rates_d(PointData& p, const BondFamilies& f, const FluidConstants& fl) {
  const auto n = static_cast<std::int64_t>(p.owned);
  const bool with_gravity = has_gravity(fl);
#pragma omp parallel for schedule(static) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (!carries_fluid(p, i)) {
      p.fluid_rate[i] = 0.0;
      continue;
    }
    const double psi_i = with_gravity ? potential<D>(p, fl, i) : p.pore_pressure[i];
    double rate = 0.0;
    for_each_conducting_bond<D>(p, f, i, [&](std::size_t j, const double*, double length) {
      const double psi_j = with_gravity ? potential<D>(p, fl, j) : p.pore_pressure[j];
      // (Saturated, 1.0 x: the same bits as without the factor.)
      rate += relative_conductivity<Unsaturated>(p, i, j) * (psi_j - psi_i) / length * p.volume[j];
    });
    p.fluid_rate[i] = fl.micro_conductivity * rate;
  }
}

// The drain bonds' share of the fluid rates, kappa0 sum_j (psi_j - psi_i) / |xi| V_j over the
// conducting drain bonds of each body point that has any (psi_j of the layer's prescribed
// pressure), added to points.fluid_rate; each bond's volume rate into the layer,
// kappa0 (psi_i - psi_j) V_i V_j / |xi|, into d.pair_flux (0 for a bond that does not conduct).
template <int D, bool Unsaturated>
void add_drain_rates(PointData& p, const BondFamilies& f, DrainBonds& d, const FluidConstants& fl) {
  const auto rows = static_cast<std::int64_t>(d.point.size());
  const bool with_gravity = has_gravity(fl);
  std::fill(d.pair_flux.begin(), d.pair_flux.end(), 0.0);
#pragma omp parallel for schedule(static) if (thread_bond_loop(d.bond_count()))
  for (std::int64_t r = 0; r < rows; ++r) {
    const auto row = static_cast<std::size_t>(r);
    const auto i = static_cast<std::size_t>(d.point[row]);
    const double psi_i = with_gravity ? potential<D>(p, fl, i) : p.pore_pressure[i];
    double rate = 0.0;
    for_each_drain_bond(p, f, d, row, [&](std::size_t j, const double*, double length, std::size_t b) {
      const double psi_j = with_gravity ? potential<D>(p, fl, j) : p.pore_pressure[j];
      const double term = relative_conductivity<Unsaturated>(p, i, j) * (psi_j - psi_i) / length * p.volume[j];
      rate += term;
      d.pair_flux[b] = -fl.micro_conductivity * term * p.volume[i];
    });
    p.fluid_rate[i] += fl.micro_conductivity * rate;
  }
}

// Adds the sources s of the fed points to their fluid rates.
void add_sources(PointData& p, const std::vector<FluidSource>& sources) {
  for (const FluidSource& s : sources)
    for (const std::int32_t i : *s.points) p.fluid_rate[static_cast<std::size_t>(i)] += s.rate;
}

double volumetric_strain(const PointData& p, std::size_t i) {
  const int D = p.dimension;
  double trace = 0.0;
  for (int a = 0; a < D; ++a) trace += p.strain[i * D * D + a * D + a];
  return trace;
}

// p = M (zeta - n0 - b tr eps) of body point i at its fluid content and last strain; unsaturated, the
// retention inverse's (NaN where it fails: the run's guard names the point).
double pressure_from_content(const PointData& p, const FluidConstants& fl, std::size_t i) {
  if (fl.retention)
    return unsaturated_pressure(*fl.retention, fl.storage(), p.fluid_content_change[i], volumetric_strain(p, i));
  return fl.biot_modulus * (p.fluid_content_change[i] - fl.biot_coefficient * volumetric_strain(p, i));
}

// k_r(p) of every point at its present pressure (the layers' at their prescribed one) into `kr`
// (sized p.total()): the flow rates' (points.relative_permeability) and the flow limit's.
void fill_relative_permeability(const PointData& p, const RetentionCurve& curve, std::vector<double>& kr) {
  const auto n = static_cast<std::int64_t>(p.total());
#pragma omp parallel for schedule(static) if (thread_point_loop(p.total()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    kr[i] = relative_permeability(curve, p.pore_pressure[i]);
  }
}

// The unsaturated flow update (see flow_update): zeta += dt rate, p by the retention inverse, and the
// stored fluid energy of each attached point booked as the trapezoid of p d zeta
// (solver/unsaturated_coupling.hpp). Returns the energy the update released.
double unsaturated_flow_update(PointData& p, const FluidConstants& fl, double dt) {
  const auto sums = exact_point_sums<1>(p, [&](std::size_t lo, std::size_t hi, ExactSums<1>& acc) {
    for (std::size_t i = lo; i < hi; ++i) {
      if (!carries_fluid(p, i)) continue;
      const double before = p.pore_pressure[i];
      const double increment = dt * p.fluid_rate[i];
      p.fluid_content_change[i] += increment;
      p.pore_pressure[i] = pressure_from_content(p, fl, i);
      if (p.detached[i]) continue;  // as in flow_update
      const double change = flow_energy_change(p, i, before, increment);
      p.fluid_energy[i] += change;
      acc[0] -= change;
    }
  });
  return sums[0];
}

// The same booking for a super step that changed the contents by `increment` from the pressures `before`.
double unsaturated_energy_released(PointData& p, const std::vector<double>& before,
                                   const std::vector<double>& increment) {
  const auto sums = exact_point_sums<1>(p, [&](std::size_t lo, std::size_t hi, ExactSums<1>& acc) {
    for (std::size_t i = lo; i < hi; ++i) {
      if (!carries_fluid(p, i) || p.detached[i]) continue;
      const double change = flow_energy_change(p, i, before[i], increment[i]);
      p.fluid_energy[i] += change;
      acc[0] -= change;
    }
  });
  return sums[0];
}

}  // namespace

void update_pressures(PointData& p, const FluidConstants& fl) {
  const auto n = static_cast<std::int64_t>(p.owned);
#pragma omp parallel for schedule(static) if (thread_point_loop(p.owned))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (carries_fluid(p, i)) p.pore_pressure[i] = pressure_from_content(p, fl, i);
  }
}

double stored_energy_released(PointData& p, const FluidConstants& fl, const std::vector<double>& before,
                              const std::vector<double>& content_increment) {
  if (fl.retention) return unsaturated_energy_released(p, before, content_increment);
  const double inv_2m = 0.5 / fl.biot_modulus;
  const auto sums = exact_point_sums<1>(p, [&](std::size_t lo, std::size_t hi, ExactSums<1>& acc) {
    for (std::size_t i = lo; i < hi; ++i) {
      if (!carries_fluid(p, i) || p.detached[i]) continue;  // as in flow_update
      const double after = p.pore_pressure[i];
      acc[0] += p.volume[i] * inv_2m * (before[i] * before[i] - after * after);
    }
  });
  return sums[0];
}

double lattice_micro_conductivity(int dimension, double spacing, double horizon, double thickness, double mobility) {
  const double cell = dimension == 3 ? spacing * spacing * spacing : spacing * spacing * thickness;
  double sum = 0.0;
  for_each_family_offset(dimension, horizon / spacing, [&](int x, int y, int z) {
    sum += spacing * std::sqrt(static_cast<double>(x * x + y * y + z * z)) * cell;
  });
  return 2.0 * dimension * mobility / sum;
}

FluidConstants fluid_constants(const Scene& scene) {
  const PoreFluidParameters& pf = *scene.material.pore_fluid;
  FluidConstants fl;
  fl.biot_coefficient = pf.biot_coefficient;
  fl.biot_modulus = pf.biot_modulus;
  fl.porosity = scene.material.porosity();
  fl.fluid_density = pf.fluid_density;
  fl.mobility = pf.mobility();
  fl.micro_conductivity = lattice_micro_conductivity(scene.dimension, scene.geometry.spacing, scene.geometry.horizon(),
                                                     scene.thickness, fl.mobility);
  if (scene.effects.gravity) fl.gravity = scene.gravity;
  fl.retention = retention_curve(pf);
  return fl;
}

void start_fluid(PointData& p, const FluidConstants& fl, double initial_pressure, std::optional<double> free_surface) {
  const int D = p.dimension;
  const double g =
      std::sqrt(fl.gravity[0] * fl.gravity[0] + fl.gravity[1] * fl.gravity[1] + fl.gravity[2] * fl.gravity[2]);
  for (std::size_t i = 0; i < p.total(); ++i) {
    const bool body = carries_fluid(p, i);
    double p0 = initial_pressure;
    if (free_surface && g > 0.0) {
      // rho_f |g| (H - up . x) = rho_f (|g| H + g . x): the potential p - rho_f g . x is rho_f |g| H.
      double gx = 0.0;
      for (int a = 0; a < D; ++a) gx += fl.gravity[a] * p.position[i * D + a];
      p0 = fl.fluid_density * (g * *free_surface + gx);
    }
    p.pore_pressure[i] = body ? p0 : 0.0;
    p.fluid_content_change[i] = body ? p0 / fl.biot_modulus : 0.0;
    // Unsaturated under suction: the content of the retention curve at zero strain.
    if (body && fl.retention && p0 < 0.0)
      p.fluid_content_change[i] = fluid_content_change(*fl.retention, fl.storage(), p0, 0.0);
    p.fluid_rate[i] = 0.0;
  }
  if (fl.retention) {  // the work received counts from the start (solver/unsaturated_coupling.hpp)
    p.fluid_energy.assign(p.total(), 0.0);
    p.relative_permeability.assign(p.total(), 1.0);
  }
}

void fluid_rates(PointData& p, const BondFamilies& f, const FluidConstants& fl) {
  if (fl.retention) {
    fill_relative_permeability(p, *fl.retention, p.relative_permeability);
    if (p.dimension == 2)
      fluid_rates_d<2, true>(p, f, fl);
    else
      fluid_rates_d<3, true>(p, f, fl);
  } else if (p.dimension == 2) {
    fluid_rates_d<2, false>(p, f, fl);
  } else {
    fluid_rates_d<3, false>(p, f, fl);
  }
}

void flow_rates(PointData& p, const BondFamilies& f, const FluidConstants& fl, FlowBoundaries* boundaries) {
  fluid_rates(p, f, fl);
  DrainBonds* drains = boundaries ? boundaries->drains : nullptr;
  if (drains) {  // (fluid_rates refreshed k_r)
    if (fl.retention)
      p.dimension == 2 ? add_drain_rates<2, true>(p, f, *drains, fl) : add_drain_rates<3, true>(p, f, *drains, fl);
    else
      p.dimension == 2 ? add_drain_rates<2, false>(p, f, *drains, fl) : add_drain_rates<3, false>(p, f, *drains, fl);
  }
  if (boundaries) add_sources(p, boundaries->sources);
}

void drained_outflow_rates(const DrainBonds& d, std::vector<double>& rates) {
  rates.assign(d.drain_count, 0.0);
  for (std::size_t b = 0; b < d.bond_count(); ++b) rates[static_cast<std::size_t>(d.drain[b])] += d.pair_flux[b];
}

double flow_update(PointData& p, const BondFamilies& f, const FluidConstants& fl, double dt,
                   FlowBoundaries* boundaries) {
  flow_rates(p, f, fl, boundaries);
  if (DrainBonds* drains = boundaries ? boundaries->drains : nullptr) {
    drained_outflow_rates(*drains, drains->outflow);
    for (double& v : drains->outflow) v *= dt;
  }
  if (fl.retention) return unsaturated_flow_update(p, fl, dt);
  const double inv_2m = 0.5 / fl.biot_modulus;
  const auto sums = exact_point_sums<1>(p, [&](std::size_t lo, std::size_t hi, ExactSums<1>& acc) {
    for (std::size_t i = lo; i < hi; ++i) {
      if (!carries_fluid(p, i)) continue;
      const double before = p.pore_pressure[i];
      p.fluid_content_change[i] += dt * p.fluid_rate[i];
      const double after = pressure_from_content(p, fl, i);
      p.pore_pressure[i] = after;
      // A detached point keeps its fluid (the mass balance counts it) but
      // stores no energy (kernel::elastic_energy_of_point; its strain is zero):
      // its change is not the flow's.
      if (!p.detached[i]) acc[0] += p.volume[i] * inv_2m * (before * before - after * after);
    }
  });
  return sums[0];
}

double fluid_step_limit(const PointData& p, const BondFamilies& f, const FluidConstants& fl, const DrainBonds* drains) {
  // Unsaturated: each row of the linearized flow, sum_j kappa_ij V_j / |xi| over the point's tangent
  // capacity d zeta / dp (docs/theory.md section 12); saturated the capacity is 1/M everywhere. The
  // largest row is a max, the same for any thread count. k_r of the present pressures in a vector of
  // its own (the points are not changed).
  const bool unsaturated = fl.retention.has_value();
  std::vector<double> kr;
  if (unsaturated) {
    kr.resize(p.total());
    fill_relative_permeability(p, *fl.retention, kr);
  }
  const auto factor = [&](std::size_t i, std::size_t j) { return unsaturated ? 0.5 * (kr[i] + kr[j]) : 1.0; };
  const auto n = static_cast<std::int64_t>(p.owned);
  double largest = 0.0;
#pragma omp parallel for schedule(static) reduction(max : largest) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (!carries_fluid(p, i)) continue;
    double sum = 0.0;
    auto add = [&](std::size_t j, const double*, double length) { sum += factor(i, j) * p.volume[j] / length; };
    if (p.dimension == 2)
      for_each_conducting_bond<2>(p, f, i, add);
    else
      for_each_conducting_bond<3>(p, f, i, add);
    if (const std::ptrdiff_t row = drains ? drains->row_of(i) : -1; row >= 0)
      for_each_drain_bond(p, f, *drains, static_cast<std::size_t>(row),
                          [&](std::size_t j, const double*, double length, std::size_t) {
                            sum += factor(i, j) * p.volume[j] / length;
                          });
    if (unsaturated && sum > 0.0)
      sum /= fl.biot_modulus *
             fluid_content_derivative(*fl.retention, fl.storage(), p.pore_pressure[i], volumetric_strain(p, i));
    largest = std::max(largest, sum);
  }
  const double rate = fl.biot_modulus * fl.micro_conductivity * largest;
  return rate > 0.0 ? 1.0 / rate : std::numeric_limits<double>::infinity();
}

double fluid_volume(const PointData& p, const FluidConstants& fl) {
  const auto sums = exact_point_sums<2>(p, [&](std::size_t lo, std::size_t hi, ExactSums<2>& acc) {
    for (std::size_t i = lo; i < hi; ++i) {
      if (!carries_fluid(p, i)) continue;
      acc[0] += p.volume[i];
      acc[1] += p.volume[i] * p.fluid_content_change[i];
    }
  });
  return fl.porosity * sums[0] + sums[1];
}

FlowSchedule flow_schedule(double fluid_step, double dt, FlowIntegration integration) {
  FlowSchedule s;
  s.fluid_step = fluid_step;
  s.integration = integration;
  const double usable = 0.9 * fluid_step;
  if (usable >= dt) {
    // At most kLongestFlowInterval steps between updates: each batch's pressure change is a step in
    // the forces, which rings the skeleton at the batch period (docs/theory.md section 12).
    const double steps = std::min(std::floor(usable / dt), static_cast<double>(kLongestFlowInterval));
    s.interval = std::max<std::int64_t>(1, static_cast<std::int64_t>(steps));
  } else {
    s.substeps = static_cast<std::int64_t>(std::ceil(dt / usable));
    const std::int64_t stages = rkl2_stages(dt, fluid_step);
    if (integration == FlowIntegration::automatic && stages < s.substeps) {
      s.stages = stages;
      s.substeps = 1;
    }
  }
  return s;
}

FlowSchedule unsaturated_flow_schedule(double fluid_step, double dt, FlowIntegration integration) {
  FlowSchedule s = flow_schedule(fluid_step, dt, integration);
  s.interval = 1;
  s.follows_saturation = true;
  return s;
}

namespace {
template <int D>
void darcy_velocity_d(const PointData& p, const BondFamilies& f, const FluidConstants& fl, std::size_t i, double* q,
                      const DrainBonds* drains) {
  for (int a = 0; a < D; ++a) q[a] = 0.0;
  if (!carries_fluid(p, i) || p.detached[i]) return;
  Eigen::Matrix<double, D, D> k = Eigen::Matrix<double, D, D>::Zero();
  Eigen::Matrix<double, D, 1> s = Eigen::Matrix<double, D, 1>::Zero();
  auto add = [&](std::size_t j, const double* xi) {
    const Eigen::Map<const Eigen::Matrix<double, D, 1>> x(xi);
    k += p.volume[j] * x * x.transpose();
    s += p.volume[j] * (p.pore_pressure[j] - p.pore_pressure[i]) * x;
  };
  for_each_conducting_bond<D>(p, f, i, [&](std::size_t j, const double* xi, double) { add(j, xi); });
  const std::ptrdiff_t row = drains ? drains->row_of(i) : -1;
  if (row >= 0)
    for_each_drain_bond(p, f, *drains, static_cast<std::size_t>(row),
                        [&](std::size_t j, const double* xi, double, std::size_t) { add(j, xi); });
  const Eigen::FullPivLU<Eigen::Matrix<double, D, D>> lu(k);
  if (!lu.isInvertible()) return;
  const Eigen::Matrix<double, D, 1> gradient = lu.solve(s);
  const double mobility =
      fl.retention ? fl.mobility * relative_permeability(*fl.retention, p.pore_pressure[i]) : fl.mobility;
  for (int a = 0; a < D; ++a) q[a] = -mobility * (gradient(a) - fl.fluid_density * fl.gravity[a]);
}
}  // namespace

void darcy_velocity(const PointData& p, const BondFamilies& f, const FluidConstants& fl, std::size_t i, double* q,
                    const DrainBonds* drains) {
  if (p.dimension == 2)
    darcy_velocity_d<2>(p, f, fl, i, q, drains);
  else
    darcy_velocity_d<3>(p, f, fl, i, q, drains);
}

}  // namespace mppm::solver
