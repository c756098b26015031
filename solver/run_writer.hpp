// The run directory of mppm-solve (docs/stages.md, common/run_directory.hpp, common/snapshot_file.hpp):
// resolved scene, reference points, snapshots, load.csv, energy.csv, log.txt, run_info.json, and
// with damage crack_path.csv (common/crack_path.hpp).
// Tables and the log are kept in memory and rewritten atomically (flush) after snapshots, at most
// once a second of wall time, and at checkpoints, stops and the end (solve_run.cpp), so no file is
// ever half-written under its final name. A snapshot (and the resolved scene and the reference) is
// renamed to its name as soon as it is written, and made durable (fsync) in a batch by the next
// flush, before run_info.json lists it: one flush is one batch of fsyncs (common/atomic_file.hpp,
// StagedFiles), whatever the number of files.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/output_directory.hpp"
#include "common/scene.hpp"
#include "common/snapshot_file.hpp"
#include "solver/partition_summary.hpp"
#include "solver/phase_timer.hpp"
#include "solver/point_data.hpp"
#include "solver/pore_fluid.hpp"

namespace mppm::solver {

struct RunInfo {
  std::string status = "running";  // running | completed | numerical_failure | interrupted | write_error
  std::string message;
  std::uint64_t points = 0, bonds = 0;
  std::int64_t steps = 0;
  double time = 0.0;
  double wall_seconds = 0.0;       // the whole run: reading, families, critical step, loop, files
  double loop_wall_seconds = 0.0;  // the time loop from its first step (snapshot and row writing included)
  // The start-up before the first step, phase by phase in their order (solver/phase_timer.hpp);
  // their sum is wall_seconds - loop_wall_seconds.
  std::vector<PhaseTimer::Phase> start_up;
  int threads = 1;  // per process
  // A distributed run (mppm-solve under mpirun): how its points and bonds are shared; written as
  // "processes" and "partition" (a one-process run: "processes": 1 and no partition).
  std::optional<PartitionSummary> partition;
  std::vector<std::string> effects;
  int dimension = 2;
  double time_step = 0.0, critical_time_step = 0.0;
  double largest_time_step = 0.0;  // the bound the step must respect (lower with damage)
  // Where the critical step was estimated: "patch" or "whole_model" (docs/theory.md section 9).
  std::string critical_step_estimate;
  std::string limiting_mode;
  std::uint64_t detached_points = 0;
  // Pore fluid: the fluid step limit and the flow schedule (written only with the effect).
  std::optional<FlowSchedule> flow;
};

class RunWriter {
 public:
  // Creates RUN_DIR (and RUN_DIR/snapshots). An existing non-empty directory is refused with an
  // InputError naming it and --force unless `force`, which replaces an earlier run directory as
  // a whole (common/output_directory.hpp): no snapshot of the older run survives.
  RunWriter(std::string directory, bool force);
  // A restart (mppm-solve --restart): opens the existing run directory as it is; the tables, log
  // and snapshot list are put back with restore_* before anything is written.
  struct ContinueExisting {};
  RunWriter(std::string directory, ContinueExisting);
  // The processes of a distributed run other than the first: the same tables and log are kept, so
  // that the run loop is the same code on every process, but no file is touched (the first
  // process writes the run directory; docs/theory.md section 13).
  struct Silent {};
  RunWriter(std::string directory, Silent);
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  const std::string& directory() const { return directory_; }
  std::string path(const std::string& name) const { return directory_ + "/" + name; }

  // `derived`: values the solver derived (written under `derived:`), e.g. the time step.
  // Returns the text written (its fingerprint identifies the scene of a checkpoint).
  std::string write_resolved_scene(const Scene& scene, const std::vector<std::pair<std::string, double>>& derived = {});
  // `fields`: reference_fields of the points, or of all processes' points gathered.
  void write_reference(int dimension, std::uint64_t point_count, const std::vector<SnapshotFieldSource>& fields);
  // Named by its step. The fields are written as they are produced (common/snapshot_file.hpp), not
  // assembled first, to a temporary file, which is then renamed to its name: complete under its
  // name at once for every reader. It is made durable (fsync) with the snapshots since the last
  // flush(), by that flush, before run_info.json lists it: one journal commit for the batch
  // instead of one per snapshot (a background fsync per snapshot cost the crack-branching base
  // case about 5 % of its time on a 2-core machine). A snapshot written after the last flush is not
  // listed yet; after a crash of the machine it may be lost, and its checksum tells.
  void write_snapshot(int dimension, std::int64_t step, double time, std::uint64_t point_count,
                      const std::vector<SnapshotFieldSource>& fields);

  void set_load_header(const std::vector<std::string>& columns, bool pore_fluid = false);
  void add_load_row(const std::vector<double>& values);
  void add_energy_row(const std::vector<double>& values);
  void log(const std::string& line);  // also kept for log.txt
  // Damage runs: crack_path.csv, rewritten by every flush (before run_info.json, so that it covers
  // at least the time run_info.json gives). Rows are only added: a point's row never changes.
  void start_crack_path_table();
  void add_crack_path_row(std::uint64_t point, const std::array<double, 3>& position, double time);
  std::size_t crack_path_rows() const { return crack_path_rows_; }

  // Rewrites load.csv, energy.csv, log.txt, crack_path.csv and run_info.json, each atomically, in
  // one batch (StagedFiles) that also makes the files written since the last flush durable;
  // run_info.json is renamed last, once the others are on disk. Throws InputError naming a file
  // that fails; the files of the last flush stay then.
  void flush(const RunInfo& info);

  // The tables and the snapshot list so far (what a checkpoint records of them, after a flush) and
  // their restoration on a restart.
  struct SnapshotRecord {
    std::string file;  // relative to the run directory
    std::int64_t step;
    double time;
  };
  const std::vector<SnapshotRecord>& snapshots() const { return snapshots_; }
  const std::string& load_table() const { return load_csv_; }
  const std::string& energy_table() const { return energy_csv_; }
  void restore_tables(std::string load_csv, std::string energy_csv) {
    load_csv_ = std::move(load_csv);
    energy_csv_ = std::move(energy_csv);
  }
  void restore_log(std::string log) { log_ = std::move(log); }
  void restore_snapshots(std::vector<SnapshotRecord> snapshots) { snapshots_ = std::move(snapshots); }

 private:
  std::string directory_;
  // The run directory replaced by --force, deleted beside the run (waited for by the destructor).
  std::optional<EarlierOutputRemoval> earlier_output_;
  bool silent_ = false;
  std::string load_csv_, energy_csv_, log_;
  std::optional<std::string> crack_path_csv_;  // damage runs only
  std::size_t crack_path_rows_ = 0;
  std::vector<SnapshotRecord> snapshots_;
  // Snapshots complete under their names but not yet fsynced (listed after the next flush).
  std::vector<SnapshotRecord> not_yet_durable_;
  // The resolved scene and the reference, complete under their names but not yet fsynced (made
  // durable by the first flush, which a new run makes at its first step's snapshot).
  std::vector<std::string> not_yet_durable_files_;
};

// The reference configuration's fields (run_layout::reference): position (3 components), volume,
// region, boundary id.
std::vector<SnapshotFieldSource> reference_fields(const PointData& points);

// Formats a number for the tables (shortest text that reads back to the same double).
std::string format_number(double v);

}  // namespace mppm::solver
