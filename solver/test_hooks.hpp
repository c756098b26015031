// The test hooks of mppm-solve (solver/README.md "Test hooks"): faults a test asks for on purpose
// (a NaN in one point, a velocity kick, an interruption, a failing checkpoint write), parsed from
// their options, checked against the run, and applied by the run driver (solve_run.cpp) at the
// points of a step where they act. The integrator and the checkpoint writer hold none of them.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solver/model.hpp"

namespace mppm::solver {

// mppm-solve --inject-nan: a quiet NaN written into one component of one point's state in the
// middle of a step, after its force evaluation and before its second half kick, as a singular local
// update would leave it. The per-step guard then sees it in the same step, before the next force
// evaluation spreads it to the neighbours.
struct NanInjection {
  enum class Field { displacement, velocity, rotation, rotation_rate, force };
  std::int64_t step = 1;  // the step (1-based) in which the value turns NaN
  std::size_t point = 0;  // index in the points file (owned points come first, in file order)
  Field field = Field::velocity;
  int component = 0;
  static const char* name(Field f);
};

// mppm-solve --inject-kick: `velocity` m/s added to one component of one point's velocity in the
// middle of a step, at the same place as a NaN injection. Nothing accounts for the kinetic energy
// it adds, so the periodic energy check sees unexplained growth for a known reason.
struct VelocityKick {
  std::int64_t step = 1;  // the step (1-based) in which the velocity jumps
  std::size_t point = 0;  // index in the points file
  int component = 0;
  double velocity = 0.0;  // [m/s]
};

struct TestHooks {
  std::optional<NanInjection> inject_nan;   // --inject-nan STEP:POINT[:FIELD[:COMPONENT]]
  std::optional<VelocityKick> inject_kick;  // --inject-kick STEP:POINT:COMPONENT:VELOCITY
  // The run stops after this step as if SIGTERM had arrived during it (0 = never; library only) ...
  std::int64_t interrupt_after_step = 0;
  // ... and the k-th checkpoint this process writes fails halfway as on a full disk (0 = none;
  // --fail-checkpoint-write K).
  int fail_checkpoint_write = 0;

  // Exit 2 (InputError naming the option) when a hook cannot act on this run, before anything is
  // written: a point or component the model does not have (`points`: the whole model's, of every
  // process) ...
  void check_against_model(const Model& model, std::uint64_t points, const std::string& points_file) const;
  // ... a step beyond the run ...
  void check_against_steps(std::int64_t steps) const;
  // ... or a fault hook with --restart.
  void refuse_with_restart() const;
  // The log's lines saying which fault hooks are armed.
  std::vector<std::string> armed() const;

  // Between the force evaluation and the second half kick of step `step` (1-based): the NaN and
  // the kick of that step. POINT is the point's index in the points file: in a distributed run the
  // process that owns it acts.
  void after_forces(PointData& points, std::int64_t step) const;
  // The run stops after step `step` as if interrupted.
  bool interrupts_after(std::int64_t step) const { return interrupt_after_step == step; }
  // The `written`-th checkpoint write (1-based) fails.
  bool fails_checkpoint_write(int written) const { return fail_checkpoint_write == written; }
};

// Parses the value of --inject-nan: STEP:POINT[:FIELD[:COMPONENT]] with STEP >= 1, POINT the
// 0-based index in the points file, FIELD displacement, velocity (default), rotation,
// rotation_rate or force, COMPONENT 0-based (default 0). Throws InputError naming the option.
NanInjection parse_nan_injection(const std::string& value);
// Parses the value of --inject-kick: STEP:POINT:COMPONENT:VELOCITY, VELOCITY in m/s (a number,
// units allowed: "50 m/s"). Throws InputError naming the option.
VelocityKick parse_velocity_kick(const std::string& value);
// Parses the value of --fail-checkpoint-write: K >= 1. Throws InputError naming the option.
int parse_checkpoint_write_failure(const std::string& value);

}  // namespace mppm::solver
