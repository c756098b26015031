// The run cost model (see run_cost_model.hpp). Every constant is a measurement on the
// development machine (2 vCPUs, AMD EPYC, Debian 12), idle: the 2-D bond costs from the time loop
// of the crack-branching plate (2-D, 16 000 points, 46 bonds per point) with each effect set
// (workflows/benchmarks/results.md, 2026-12-06), the 3-D ones from 3-D blocks (216 000 points with
// 31 bonds per point, and the 1-million-point block with the full model, 2026-12-03), the start-up
// from whole runs of 2 752 to 1 021 216 points (2026-12-07).
#include "common/run_cost_model.hpp"

#include <algorithm>
#include <cmath>

namespace mppm {

namespace {

bool has(const std::vector<std::string>& effects, const char* name) {
  return std::find(effects.begin(), effects.end(), name) != effects.end();
}

// One bond update of the non-polar elastic model, one thread: 2-D 5.54 s / (2000 x 737 752);
// 3-D 1 / 7.0e7 (the 216 000-point block in 2026-12-03; the same block measured 1.33e8 on 2026-12-07,
// but the 1-million-point block's full model, 0.78 s per step at 2 threads, is within 7 % of these
// 3-D constants: a large 3-D run is bound by memory, and it is the one a user estimates).
constexpr double kBaseSeconds2d = 3.75e-9, kBaseSeconds3d = 14.3e-9;
// What each effect multiplies it by (the plate: micropolar 8.74 / 5.54 s; damage 11.97 / 8.74;
// viscoplasticity below. 3-D: micropolar with damage 2.9e7 against 7.0e7 updates/s, the
// full model 2.0e7). Gravity costs nothing measurable; the pore fluid 1.27x (1 thread) and 1.25x
// (2 threads) on the plate with a flow update every 4 steps (make -C workflows/benchmarks pore-fluid;
// a flow faster than the step costs its substeps or RKL2 stages on top, which this factor leaves out).
constexpr double kMicropolar2d = 1.58, kMicropolar3d = 1.87;
constexpr double kDamage2d = 1.37, kDamage3d = 1.29;
constexpr double kViscoplasticity2d = 1.58, kViscoplasticity3d = 1.45;
// 2-D viscoplasticity also costs per point (the return map, the plastic state): with the bond factor
// above, 91 ns per point and step fits both measured micropolar viscoplastic runs' loops, the plate
// (46 bonds per point, 8.37 ms per step: 16.73 s for 2000 steps) and the shear band (12 bonds per
// point, 0.673 ms per step: workflows/accuracy-cost/estimates.md, its start-up taken off), on one
// thread. A factor alone put the shear band at 0.62 of its time. 3-D has one measurement: its
// factor holds both parts. A run whose plastic flow spreads costs more per step as it goes, which
// a scene does not tell: the whole shear band takes 0.98 ms per step (28.1 s, estimated 19.3 s).
constexpr double kViscoplasticSecondsPerPoint2d = 91e-9;
constexpr double kPoreFluid = 1.26;
// The factor above holds the plate's quarter of a flow update per step; each further flow-rate
// evaluation per step (substeps, RKL2 stages) costs about 3.8 ns per bond on one thread: the
// saturated shear band at k = 1e-10 m^2 (31 stages per step) took 334 s against 69 s at 1e-13 (an
// update every 4 steps), 57 760 steps of 39 172 bonds (workflows/saturated-shear-band, idle machine).
constexpr double kPoreFluidEvaluationsInFactor = 0.25;
constexpr double kFlowEvaluationSecondsPerBond = 3.8e-9;
// Two threads run the plate's loop 1.92-2.02x as fast as one: 0.95 per doubling of the threads.
constexpr double kEfficiencyPerDoubling = 0.95;
// The start-up: a fixed part (the critical step and the mode's naming, both on patches of a few
// hundred points whatever the body's size, and the run directory's files and their fsyncs) and the
// rest, which grows with the model (reading the points, the families, the stiffest points, the
// first forces and the reference snapshot), about 3.5 steps of the model. Measured (median of 3,
// 2026-12-07): 2-D 0.036-0.075 s for 3 372 to 16 000 points; 3-D 0.076-0.104 s for 2 752 points,
// and,
// in steps of this model's cost beyond the fixed part, the 216 000-point block 4.1 (non-polar,
// 0.28 s) and 3.6 (the full model, 0.72 s), the 1-million-point block 3.3 (full, 2.88 s), all at
// 2 threads. The 2-D plate is about 4 (0.067 s at 2 threads, micropolar).
constexpr double kStartUpFixedSeconds2d = 0.06, kStartUpFixedSeconds3d = 0.09;
constexpr double kStartUpSteps = 3.5;
// A snapshot: each value computed (a stress or damage is a small loop per point), checksummed and
// written: about 10 ns per value (the crack-branching case writes 665 MB of snapshots in a run
// whose loop alone takes 15 s of its 24 s).
constexpr double kSnapshotSecondsPerValue = 10e-9;

double elastic_seconds_per_update(int dimension, bool micropolar) {
  const double base = dimension == 3 ? kBaseSeconds3d : kBaseSeconds2d;
  return micropolar ? base * (dimension == 3 ? kMicropolar3d : kMicropolar2d) : base;
}

}  // namespace

RunCostEstimate estimate_run_cost(const RunCostInput& in) {
  RunCostEstimate e;
  double update = elastic_seconds_per_update(in.dimension, has(in.effects, "micropolar"));
  if (has(in.effects, "damage")) update *= in.dimension == 3 ? kDamage3d : kDamage2d;
  if (has(in.effects, "viscoplasticity")) update *= in.dimension == 3 ? kViscoplasticity3d : kViscoplasticity2d;
  if (has(in.effects, "pore_fluid")) update *= kPoreFluid;
  e.seconds_per_bond_update = update;
  const double threads = std::max(1, in.threads);
  e.thread_speed_up = threads * std::pow(kEfficiencyPerDoubling, std::log2(threads));
  const auto bonds = static_cast<double>(in.bonds);
  const double extra_flow =
      has(in.effects, "pore_fluid") ? std::max(0.0, in.flow_evaluations_per_step - kPoreFluidEvaluationsInFactor) : 0.0;
  const double per_point =
      has(in.effects, "viscoplasticity") && in.dimension == 2 ? kViscoplasticSecondsPerPoint2d : 0.0;
  e.seconds_per_step =
      (bonds * (update + extra_flow * kFlowEvaluationSecondsPerBond) + static_cast<double>(in.points) * per_point) /
      e.thread_speed_up;
  e.snapshot_seconds =
      kSnapshotSecondsPerValue * static_cast<double>(in.points) * static_cast<double>(in.snapshot_values_per_point);
  e.loop_seconds = static_cast<double>(std::max<std::int64_t>(0, in.steps)) * e.seconds_per_step +
                   static_cast<double>(std::max<std::int64_t>(0, in.snapshots)) * e.snapshot_seconds;
  e.start_up_seconds = (in.dimension == 3 ? kStartUpFixedSeconds3d : kStartUpFixedSeconds2d) +
                       kStartUpSteps * bonds * update / e.thread_speed_up;
  e.total_seconds = e.start_up_seconds + e.loop_seconds;
  return e;
}

}  // namespace mppm
