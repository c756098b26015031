// Checkpoint and restart of a run (README "Checkpoints and restart"): the state a run carries from
// one step to the next, written to RUN_DIR/checkpoint/state.ckpt (common/checkpoint_file.hpp), and
// put back so that the continued run is bit for bit the run that was never stopped.
//
// What is carried, and so stored (an effect that is off stores nothing of its own):
//  - always: displacement, velocity (and with micropolar rotation, rotation rate), the force and
//    moment of the last evaluation (the next step's first half kick uses them), the external force
//    density of that evaluation, step, time, the energies and their accumulators (external work,
//    dissipations, initial total), the energy check's history, the schedules of rows, snapshots and
//    checkpoints, the worst balance error, the snapshot list and the tables written so far (their
//    length and fingerprint: the tables stay in load.csv / energy.csv);
//  - viscoplasticity: plastic strain, plastic wryness, equivalent plastic strain, cohesion, the
//    last step's dissipation, and the strain and wryness of the last evaluation (the return map
//    starts the step from them);
//  - damage: bond flags and bond work, the shape tensors and stabilization factors (breaks change
//    them), detached and no-fail flags, the last evaluation's displacement, rotation and force /
//    moment tensors (the bond-work increment starts from them; by columns, as stored: a checkpoint
//    written when they were stored by rows is refused), the broken-bond and detachment
//    counters, and the crack arrivals (the points on the crack path and when each got there: a
//    restart writes crack_path.csv from them). A damage checkpoint without them (written before
//    the table existed) is refused with a message: the times of the points already on the path
//    cannot be recovered.
// Not stored: what the points file and the scene rebuild identically (positions, volumes, regions,
// families, pre-crack cuts, the start-up shape tensors without damage) and scratch that every step
// rewrites before reading it (the per-point energies, the start-of-step copies of the integrator).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/checkpoint_file.hpp"
#include "common/point_cloud.hpp"
#include "solver/energy_guard.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/model.hpp"
#include "solver/process_group.hpp"
#include "solver/run_writer.hpp"

namespace mppm::solver {

// The run loop's own state between two steps, besides the model and the integrator.
struct RunLoopState {
  double next_row = 1.0, next_snapshot = 1.0, next_checkpoint = 1.0;  // the schedules' next multiples
  double worst_balance = 0.0;
  EnergyGuard::History guard;
  std::vector<RunWriter::SnapshotRecord> snapshots;
  // The tables written so far: their length in bytes and FNV-1a fingerprint. A restart keeps this
  // much of load.csv / energy.csv (which the run flushes before every checkpoint) and drops the rows
  // a run wrote after the checkpoint.
  std::uint64_t load_table_bytes = 0, load_table_fingerprint = 0;
  std::uint64_t energy_table_bytes = 0, energy_table_fingerprint = 0;
  std::string points_file;  // where the run read its points (absolute): the default of --restart
  double time_step = 0.0;   // a restart must arrive at the same step
};

// Identifies the inputs of a run: a checkpoint is refused for a run with other inputs.
struct RunIdentity {
  std::uint64_t scene_fingerprint = 0;   // FNV-1a of scene.resolved.yaml as written
  std::uint64_t points_fingerprint = 0;  // point_cloud_fingerprint
};

// FNV-1a over everything of the points the solver uses (coordinates, volumes, regions, boundary
// ids, normals, boundaries, pre-crack geometry, spacing, horizon, thickness).
std::uint64_t point_cloud_fingerprint(const PointCloud& cloud);

// A distributed run's processes (docs/theory.md section 13). Its checkpoint is the one-process file,
// byte for byte: the first process writes it, asking each row's owner for the per-point and
// per-tracked-point rows a chunk at a time (solver/distributed_snapshot.hpp); every process reads
// the whole file on a restart and takes its own rows, so that a run checkpointed on N processes
// continues on any number.
struct CheckpointProcesses {
  const ProcessGroup& group;
  std::span<const std::int32_t> part_of;  // the process of every point of the points file
};

// Writes the state after the model's and the integrator's last step to `path`, atomically.
// Throws InputError naming the file on a write error; the previous checkpoint stays as it was.
// `simulate_write_failure` is the test hook of write_checkpoint_file. Collective with `processes`
// (the write error is thrown on the first process only).
void write_checkpoint(const std::string& path, const RunIdentity& identity, const Model& model,
                      const ExplicitDynamics& dynamics, const RunLoopState& loop, bool simulate_write_failure = false,
                      const CheckpointProcesses* processes = nullptr);

// Checks that `file` is a checkpoint of this run (scene and points fingerprints, dimension, point
// count, effects) and puts its state back into the model and the integrator (after
// dynamics.initialize()). Returns the loop state. Throws InputError naming the file and what differs.
RunLoopState restore_checkpoint(const CheckpointFile& file, const RunIdentity& identity, Model& model,
                                ExplicitDynamics& dynamics, const CheckpointProcesses* processes = nullptr);

}  // namespace mppm::solver
