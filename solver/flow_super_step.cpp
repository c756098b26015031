// RKL2 super-time-stepping of the flow (see flow_super_step.hpp; docs/theory.md section 12).
#include "solver/flow_super_step.hpp"

#include <algorithm>
#include <cmath>

#include "solver/parallel_policy.hpp"

namespace mppm::solver {

std::int64_t rkl2_stages(double span, double fluid_step) {
  // (s^2 + s - 2) / 4 >= span / (0.9 fluid_step): the positive root of s^2 + s - (2 + 4 r), rounded up
  // and then checked (the root's rounding could fall just short).
  const double ratio = span / (0.9 * fluid_step);
  auto s = std::max<std::int64_t>(2, static_cast<std::int64_t>(std::ceil(0.5 * (std::sqrt(9.0 + 16.0 * ratio) - 1.0))));
  while (static_cast<double>(s * s + s - 2) < 4.0 * ratio) ++s;
  return s;
}

Rkl2Coefficients rkl2_coefficients(std::int64_t stages) {
  const auto s = static_cast<double>(stages);
  const double w1 = 4.0 / (s * s + s - 2.0);
  auto b = [](double j) { return j <= 2.0 ? 1.0 / 3.0 : (j * j + j - 2.0) / (2.0 * j * (j + 1.0)); };
  Rkl2Coefficients c;
  c.first_rate = b(1.0) * w1;
  for (std::int64_t k = 2; k <= stages; ++k) {
    const auto j = static_cast<double>(k);
    Rkl2Stage st;
    st.mu = (2.0 * j - 1.0) / j * b(j) / b(j - 1.0);
    st.nu = -(j - 1.0) / j * b(j) / b(j - 2.0);
    st.rate = st.mu * w1;
    st.start_rate = -(1.0 - b(j - 1.0)) * st.rate;
    c.stages.push_back(st);
  }
  return c;
}

namespace {

bool carries_fluid(const PointData& p, std::size_t i) { return p.region[i] == 0; }

// The stages are carried as increments D_j = Y_j - Y_0 of the fluid content (D_0 = 0): the
// combination mu D_(j-1) + nu D_(j-2) then rounds relative to the step's change, not to the
// content, whose rounding through the stages' large coefficients (mu -> 2, nu -> -1) drifted the
// fluid's books by 1e-9 of the pore volume over a long run; each stage's content is Y_0 + D_j.

// Stage 1 on the body points' fluid content (the start's content and rates kept in `work`).
void first_stage(PointData& p, double first_rate, double span, FlowSuperStepWork& w) {
  const auto n = static_cast<std::int64_t>(p.owned);
  w.start_content.assign(p.fluid_content_change.begin(), p.fluid_content_change.begin() + n);
  w.start_rate.assign(p.fluid_rate.begin(), p.fluid_rate.begin() + n);
  w.previous_increment.assign(static_cast<std::size_t>(n), 0.0);
  w.increment.assign(static_cast<std::size_t>(n), 0.0);
#pragma omp parallel for schedule(static) if (thread_point_loop(p.owned))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (!carries_fluid(p, i)) continue;
    w.increment[i] = first_rate * span * p.fluid_rate[i];
    p.fluid_content_change[i] = w.start_content[i] + w.increment[i];
  }
}

// Stage j >= 2: the increment from the two stages before; the stage before moves to
// previous_increment.
void later_stage(PointData& p, const Rkl2Stage& c, double span, FlowSuperStepWork& w) {
  const auto n = static_cast<std::int64_t>(p.owned);
#pragma omp parallel for schedule(static) if (thread_point_loop(p.owned))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (!carries_fluid(p, i)) continue;
    const double current = w.increment[i];
    w.increment[i] = c.mu * current + c.nu * w.previous_increment[i] +
                     span * (c.rate * p.fluid_rate[i] + c.start_rate * w.start_rate[i]);
    w.previous_increment[i] = current;
    p.fluid_content_change[i] = w.start_content[i] + w.increment[i];
  }
}

// The same combination for the volumes let out per drained condition (zero at the start).
void outflow_stage(const Rkl2Stage* c, double first_rate, double span, const std::vector<double>& rates,
                   FlowSuperStepWork& w) {
  if (!c) {
    w.start_outflow = rates;
    w.previous_outflow.assign(rates.size(), 0.0);
    w.outflow.resize(rates.size());
    for (std::size_t k = 0; k < rates.size(); ++k) w.outflow[k] = first_rate * span * rates[k];
    return;
  }
  for (std::size_t k = 0; k < rates.size(); ++k) {
    const double current = w.outflow[k];
    w.outflow[k] = c->mu * current + c->nu * w.previous_outflow[k] +
                   span * (c->rate * rates[k] + c->start_rate * w.start_outflow[k]);
    w.previous_outflow[k] = current;
  }
}

}  // namespace

double flow_super_step(PointData& p, const BondFamilies& f, const FluidConstants& fl, double span, std::int64_t stages,
                       FlowBoundaries* boundaries, const std::vector<double>& pressure_before,
                       FlowSuperStepWork& work) {
  const Rkl2Coefficients c = rkl2_coefficients(stages);
  // With drain bonds, drains->outflow holds each stage's outflow rates and work.outflow the volumes.
  DrainBonds* drains = boundaries ? boundaries->drains : nullptr;
  auto stage = [&](const Rkl2Stage* coefficients) {
    flow_rates(p, f, fl, boundaries);
    if (coefficients)
      later_stage(p, *coefficients, span, work);
    else
      first_stage(p, c.first_rate, span, work);
    if (drains) {
      drained_outflow_rates(*drains, drains->outflow);
      outflow_stage(coefficients, c.first_rate, span, drains->outflow, work);
    }
    update_pressures(p, fl);
  };
  stage(nullptr);
  for (const Rkl2Stage& coefficients : c.stages) stage(&coefficients);
  if (drains) drains->outflow = work.outflow;
  return stored_energy_released(p, fl, pressure_before, work.increment);
}

}  // namespace mppm::solver
