// Writing the run directory.
#include "solver/run_writer.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <system_error>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/crack_path.hpp"
#include "common/input_error.hpp"
#include "common/json_quote.hpp"
#include "common/output_directory.hpp"
#include "common/run_directory.hpp"

namespace mppm::solver {

namespace fs = std::filesystem;

std::string format_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

namespace {

std::string csv_row(const std::vector<double>& values) {
  std::string row;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) row += ',';
    row += format_number(values[k]);
  }
  return row + '\n';
}

// {"read_points": 0.12, "bond_families": 0.8, ...}: the phases in their order, keyed by their
// names in snake case ("pre-crack cuts" -> "pre_crack_cuts").
std::string start_up_json(const std::vector<PhaseTimer::Phase>& phases) {
  std::string j = "{";
  for (std::size_t k = 0; k < phases.size(); ++k) {
    std::string key = phases[k].name;
    std::replace_if(
        key.begin(), key.end(), [](char c) { return c == ' ' || c == '-'; }, '_');
    j += (k ? ", " : "") + json_quote(key) + ": " + format_number(phases[k].seconds);
  }
  return j + "}";
}

// {"points": [8000, 8000], "ghosts": [...], "bonds": [...], "imbalance": 1.0}
std::string partition_json(const PartitionSummary& s) {
  auto list = [](const std::vector<std::int64_t>& v) {
    std::string out = "[";
    for (std::size_t k = 0; k < v.size(); ++k) out += (k ? ", " : "") + std::to_string(v[k]);
    return out + "]";
  };
  return "{\"points\": " + list(s.points) + ", \"ghosts\": " + list(s.ghosts) + ", \"bonds\": " + list(s.bonds) +
         ", \"imbalance\": " + format_number(s.imbalance) + "}";
}

double start_up_total(const std::vector<PhaseTimer::Phase>& phases) {
  double total = 0.0;
  for (const PhaseTimer::Phase& p : phases) total += p.seconds;
  return total;
}

// run_info.json (docs/stages.md) with `listed` as its snapshots.
std::string run_info_json(const RunInfo& info, const std::vector<RunWriter::SnapshotRecord>& listed) {
  std::string j = "{\n";
  j += "  \"status\": " + json_quote(info.status) + ",\n";
  j += "  \"message\": " + json_quote(info.message) + ",\n";
  j += "  \"points\": " + std::to_string(info.points) + ",\n";
  j += "  \"bonds\": " + std::to_string(info.bonds) + ",\n";
  j += "  \"steps\": " + std::to_string(info.steps) + ",\n";
  j += "  \"time_s\": " + format_number(info.time) + ",\n";
  j += "  \"wall_seconds\": " + format_number(info.wall_seconds) + ",\n";
  j += "  \"loop_wall_seconds\": " + format_number(info.loop_wall_seconds) + ",\n";
  j += "  \"start_up_seconds\": " + start_up_json(info.start_up) + ",\n";
  j += "  \"start_up_total_seconds\": " + format_number(start_up_total(info.start_up)) + ",\n";
  j += "  \"threads\": " + std::to_string(info.threads) + ",\n";
  j += "  \"processes\": " + std::to_string(info.partition ? info.partition->points.size() : 1) + ",\n";
  if (info.partition) j += "  \"partition\": " + partition_json(*info.partition) + ",\n";
  j += "  \"effects\": [";
  for (std::size_t k = 0; k < info.effects.size(); ++k) j += (k ? ", " : "") + json_quote(info.effects[k]);
  j += "],\n";
  j += "  \"dimension\": " + std::to_string(info.dimension) + ",\n";
  j += "  \"time_step_s\": " + format_number(info.time_step) + ",\n";
  j += "  \"critical_time_step_s\": " + format_number(info.critical_time_step) + ",\n";
  j += "  \"largest_time_step_s\": " + format_number(info.largest_time_step) + ",\n";
  j += "  \"critical_step_estimate\": " + json_quote(info.critical_step_estimate) + ",\n";
  j += "  \"limiting_mode\": " + json_quote(info.limiting_mode) + ",\n";
  if (info.flow) {
    j += "  \"fluid_time_step_s\": " + format_number(info.flow->fluid_step) + ",\n";
    j += "  \"flow_update_interval_steps\": " + std::to_string(info.flow->interval) + ",\n";
    j += "  \"flow_substeps\": " + std::to_string(info.flow->substeps) + ",\n";
    j += "  \"flow_rkl2_stages\": " + std::to_string(info.flow->stages > 1 ? info.flow->stages : 0) + ",\n";
    // Unsaturated: the schedule above is the start's; it is chosen again before every update.
    if (info.flow->follows_saturation) j += "  \"flow_follows_saturation\": true,\n";
  }
  j += "  \"snapshots\": [";
  for (std::size_t k = 0; k < listed.size(); ++k)
    j += std::string(k ? "," : "") + "\n    {\"file\": " + json_quote(listed[k].file) +
         ", \"step\": " + std::to_string(listed[k].step) + ", \"time_s\": " + format_number(listed[k].time) + "}";
  j += listed.empty() ? "],\n" : "\n  ],\n";
  j += "  \"detached_points\": " + std::to_string(info.detached_points) + "\n}\n";
  return j;
}

}  // namespace

RunWriter::RunWriter(std::string directory, bool force) : directory_(std::move(directory)) {
  const OutputDirectoryKind kind{"run directory",
                                 "-o RUN_DIR",
                                 {run_layout::run_info, run_layout::resolved_scene, run_layout::reference,
                                  run_layout::log, run_layout::snapshot_dir}};
  earlier_output_.emplace(prepare_output_directory(directory_, force, kind));
  std::error_code ec;
  fs::create_directories(fs::path(directory_) / run_layout::snapshot_dir, ec);
  if (ec) throw InputError(directory_ + ": cannot create the run directory (" + ec.message() + ")");
}

RunWriter::RunWriter(std::string directory, ContinueExisting) : directory_(std::move(directory)) {
  std::error_code ec;
  if (!fs::is_directory(directory_, ec)) throw InputError(directory_ + ": not a run directory (it does not exist)");
  fs::create_directories(fs::path(directory_) / run_layout::snapshot_dir, ec);
  if (ec) throw InputError(directory_ + ": cannot open the run directory for writing (" + ec.message() + ")");
}

RunWriter::RunWriter(std::string directory, Silent) : directory_(std::move(directory)), silent_(true) {}

std::string RunWriter::write_resolved_scene(const Scene& scene,
                                            const std::vector<std::pair<std::string, double>>& derived) {
  std::string text = resolved_scene_yaml(scene, derived);
  if (silent_) return text;
  const std::string target = path(run_layout::resolved_scene);
  rename_temporary(write_temporary(target, [&](std::ostream& out) { out << text; }), target);
  not_yet_durable_files_.push_back(target);
  return text;
}

std::vector<SnapshotFieldSource> reference_fields(const PointData& p) {
  const int D = p.dimension;
  // Position always with 3 components (z = 0 in 2-D); region and boundary id as doubles.
  return {{"position", 3,
           [&p, D](std::uint64_t first, std::uint64_t count, double* out) {
             for (std::uint64_t k = 0; k < count; ++k)
               for (int c = 0; c < 3; ++c) out[k * 3 + c] = c < D ? p.position[(first + k) * D + c] : 0.0;
           }},
          {"volume", 1,
           [&p](std::uint64_t first, std::uint64_t count, double* out) {
             for (std::uint64_t k = 0; k < count; ++k) out[k] = p.volume[first + k];
           }},
          {"region", 1,
           [&p](std::uint64_t first, std::uint64_t count, double* out) {
             for (std::uint64_t k = 0; k < count; ++k) out[k] = p.region[first + k];
           }},
          {"boundary_id", 1, [&p](std::uint64_t first, std::uint64_t count, double* out) {
             for (std::uint64_t k = 0; k < count; ++k) out[k] = p.boundary_id[first + k];
           }}};
}

void RunWriter::write_reference(int dimension, std::uint64_t point_count,
                                const std::vector<SnapshotFieldSource>& fields) {
  if (silent_) return;
  const std::string target = path(run_layout::reference);
  rename_temporary(mppm::write_snapshot_temporary(dimension, 0, 0.0, point_count, fields, target), target);
  not_yet_durable_files_.push_back(target);
}

void RunWriter::write_snapshot(int dimension, std::int64_t step, double time, std::uint64_t point_count,
                               const std::vector<SnapshotFieldSource>& fields) {
  if (silent_) return;
  const std::string file = std::string(run_layout::snapshot_dir) + "/" + run_layout::snapshot_name(step);
  const std::string target = path(file);
  rename_temporary(mppm::write_snapshot_temporary(dimension, step, time, point_count, fields, target), target);
  not_yet_durable_.push_back(SnapshotRecord{file, step, time});
}

void RunWriter::set_load_header(const std::vector<std::string>& columns, bool pore_fluid) {
  load_csv_.clear();
  for (std::size_t k = 0; k < columns.size(); ++k) load_csv_ += (k ? "," : "") + columns[k];
  load_csv_ += '\n';
  energy_csv_.clear();
  const auto e = run_files::energy_columns(pore_fluid);
  for (std::size_t k = 0; k < e.size(); ++k) energy_csv_ += (k ? "," : "") + e[k];
  energy_csv_ += '\n';
}

void RunWriter::add_load_row(const std::vector<double>& values) { load_csv_ += csv_row(values); }
void RunWriter::add_energy_row(const std::vector<double>& values) { energy_csv_ += csv_row(values); }
void RunWriter::log(const std::string& line) { log_ += line + '\n'; }

void RunWriter::start_crack_path_table() {
  std::string header;
  for (const std::string& c : run_files::crack_path_columns()) header += (header.empty() ? "" : ",") + c;
  crack_path_csv_ = header + '\n';
  crack_path_rows_ = 0;
}

void RunWriter::add_crack_path_row(std::uint64_t point, const std::array<double, 3>& position, double time) {
  std::string& table = crack_path_csv_.value();
  table += std::to_string(point);
  for (const double x : position) table += ',' + format_number(x);
  table += ',' + format_number(time) + '\n';
  ++crack_path_rows_;
}

void RunWriter::flush(const RunInfo& info) {
  if (silent_) return;
  StagedFiles files;
  files.stage(path(run_layout::load), [&](std::ostream& out) { out << load_csv_; });
  files.stage(path(run_layout::energy), [&](std::ostream& out) { out << energy_csv_; });
  files.stage(path(run_layout::log), [&](std::ostream& out) { out << log_; });
  if (crack_path_csv_) files.stage(path(run_layout::crack_path), [&](std::ostream& out) { out << *crack_path_csv_; });
  // The snapshots since the last flush join run_info.json's list, made durable in this batch with
  // the files complete under their names since then; kept as they were if the batch fails.
  std::vector<SnapshotRecord> listed = snapshots_;
  listed.insert(listed.end(), not_yet_durable_.begin(), not_yet_durable_.end());
  std::vector<std::string> complete_files = not_yet_durable_files_;
  for (const SnapshotRecord& r : not_yet_durable_) complete_files.push_back(path(r.file));
  files.stage(path(run_layout::run_info), [&](std::ostream& out) { out << run_info_json(info, listed); });
  const std::vector<std::string> snapshot_directory{path(run_layout::snapshot_dir)};
  files.commit(complete_files, not_yet_durable_.empty() ? std::vector<std::string>{} : snapshot_directory);
  snapshots_ = std::move(listed);
  not_yet_durable_.clear();
  not_yet_durable_files_.clear();
}

}  // namespace mppm::solver
