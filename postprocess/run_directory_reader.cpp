// Run directory checks. run_info.json is read with yaml-cpp (JSON is YAML's flow style), the
// only structured-text parser among the project's dependencies.
#include "postprocess/run_directory_reader.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"
#include "common/run_directory.hpp"
#include "common/units.hpp"

namespace mppm::post {
namespace fs = std::filesystem;

namespace {

template <class T>
T required(const YAML::Node& node, const char* key, const std::string& file) {
  const YAML::Node value = node[key];
  if (!value) throw InputError(file + ": key '" + key + "' is missing");
  try {
    return value.as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(file + ": key '" + key + "' has an unexpected value '" +
                     (value.IsScalar() ? value.Scalar() : std::string("(not a scalar)")) + "'");
  }
}

template <class T>
T optional_value(const YAML::Node& node, const char* key, T fallback) {
  const YAML::Node value = node[key];
  if (!value || value.IsNull()) return fallback;
  try {
    return value.as<T>();
  } catch (const YAML::Exception&) {
    return fallback;
  }
}

// A scene quantity: a number (SI) or a string with a unit.
double scene_quantity(const YAML::Node& node, const std::string& key_path, const Dimension& dimension,
                      const std::string& file) {
  if (!node || node.IsNull()) throw InputError(file + ": " + key_path + ": missing");
  if (!node.IsScalar()) throw InputError(file + ": " + key_path + ": expected a number");
  try {
    return parse_quantity_as(node.Scalar(), dimension);
  } catch (const std::exception& e) {
    throw InputError(file + ": " + key_path + ": " + e.what());
  }
}

}  // namespace

RunInfo read_run_info(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path + ": cannot be read");
  } catch (const YAML::Exception& e) {
    throw InputError(path + ": not valid JSON (" + std::string(e.what()) +
                     "); the run may have been killed while writing it");
  }
  if (!root.IsMap()) throw InputError(path + ": expected a JSON object");
  RunInfo info;
  info.status = required<std::string>(root, "status", path);
  info.message = optional_value<std::string>(root, "message", "");
  info.points = required<std::int64_t>(root, "points", path);
  info.bonds = optional_value<std::int64_t>(root, "bonds", 0);
  info.steps = optional_value<std::int64_t>(root, "steps", 0);
  info.time_s = optional_value<double>(root, "time_s", 0.0);
  info.time_step_s = optional_value<double>(root, "time_step_s", 0.0);
  info.wall_seconds = optional_value<double>(root, "wall_seconds", 0.0);
  info.threads = optional_value<int>(root, "threads", 0);
  info.dimension = required<int>(root, "dimension", path);
  info.detached_points = optional_value<std::int64_t>(root, "detached_points", 0);
  if (info.dimension != 2 && info.dimension != 3)
    throw InputError(path + ": dimension is " + std::to_string(info.dimension) + " (expected 2 or 3)");
  if (const YAML::Node effects = root["effects"]; effects && effects.IsSequence())
    for (const auto& e : effects) info.effects.push_back(e.as<std::string>());
  const YAML::Node snapshots = root["snapshots"];
  if (!snapshots || !snapshots.IsSequence()) throw InputError(path + ": key 'snapshots' is missing or not a list");
  for (const auto& s : snapshots) {
    SnapshotEntry entry;
    entry.path = required<std::string>(s, "file", path);
    entry.step = required<std::int64_t>(s, "step", path);
    entry.time = required<double>(s, "time_s", path);
    info.snapshots.push_back(entry);
  }
  return info;
}

namespace {

// Throws unless `dir` is a non-empty directory with a run_info.json; returns that file's path.
fs::path run_info_path(const std::string& path) {
  const fs::path dir(path);
  std::error_code ec;
  if (!fs::exists(dir, ec)) throw InputError(path + ": no such run directory");
  if (!fs::is_directory(dir, ec))
    throw InputError(path + ": not a directory (expected the run directory written by mppm-solve)");
  if (fs::is_empty(dir, ec))
    throw InputError(path + ": the directory is empty (expected the run directory written by mppm-solve)");
  const fs::path info_path = dir / run_layout::run_info;
  if (!fs::exists(info_path))
    throw InputError(path + ": not a run directory: " + run_layout::run_info +
                     " is missing (expected the output directory of mppm-solve)");
  return info_path;
}

// A run that did not complete is postprocessed with a note (a running one only if allowed).
void check_run_status(RunDirectory& run, const fs::path& info_path, bool allow_unfinished) {
  const std::string& status = run.info.status;
  if (status == "running") {
    if (!allow_unfinished)
      throw InputError(info_path.string() +
                       ": status is 'running': the run did not finish (it crashed or is still "
                       "running); use --partial to postprocess the snapshots written so far");
    run.notes.push_back("the run did not finish (status 'running'); postprocessed the " +
                        std::to_string(run.info.snapshots.size()) + " snapshots written so far");
  } else if (status == "numerical_failure" || status == "interrupted") {
    run.notes.push_back("the run ended with status '" + status + "'" +
                        (run.info.message.empty() ? "" : " (" + run.info.message + ")") +
                        "; postprocessed up to its last good snapshot");
  } else if (status != "completed") {
    throw InputError(info_path.string() + ": unknown status '" + status +
                     "' (expected completed, numerical_failure, interrupted or running)");
  }
}

// Snapshot paths resolved against the run directory, each file present, times increasing.
void check_snapshot_list(RunInfo& info, const fs::path& dir, const fs::path& info_path) {
  if (info.snapshots.empty())
    throw InputError(info_path.string() + ": the run lists no snapshots (nothing to postprocess)");
  for (auto& entry : info.snapshots) {
    const fs::path file = fs::path(entry.path).is_absolute() ? fs::path(entry.path) : dir / entry.path;
    entry.path = file.string();
    if (!fs::exists(file))
      throw InputError(entry.path + ": snapshot listed in " + std::string(run_layout::run_info) + " is missing");
  }
  for (std::size_t k = 1; k < info.snapshots.size(); ++k)
    if (!(info.snapshots[k].time > info.snapshots[k - 1].time))
      throw InputError(info_path.string() + ": snapshot times are not increasing (snapshot " + std::to_string(k) + ")");
}

// scene.resolved.yaml, and the spacing, horizon and thickness from it.
void read_resolved_scene(RunDirectory& run, const fs::path& dir) {
  const fs::path scene_path = dir / run_layout::resolved_scene;
  try {
    run.scene = YAML::LoadFile(scene_path.string());
  } catch (const YAML::BadFile&) {
    throw InputError(scene_path.string() + ": missing or unreadable (every run directory has it)");
  } catch (const YAML::Exception& e) {
    throw InputError(scene_path.string() + ": not valid YAML (" + std::string(e.what()) + ")");
  }
  const std::string scene_file = scene_path.string();
  if (!run.scene.IsMap()) throw InputError(scene_file + ": expected a YAML map");
  run.spacing = scene_quantity(run.scene["geometry"]["spacing"], "geometry.spacing", dim::length, scene_file);
  const double factor =
      scene_quantity(run.scene["geometry"]["horizon_factor"], "geometry.horizon_factor", dim::none, scene_file);
  run.horizon = factor * run.spacing;
  if (!(run.spacing > 0) || !(factor > 0))
    throw InputError(scene_file + ": geometry.spacing and geometry.horizon_factor must be positive");
  if (run.scene["thickness"])
    run.thickness = scene_quantity(run.scene["thickness"], "thickness", dim::length, scene_file);
}

// reference.snap, checked against run_info.json and for the fields the postprocessor needs.
void read_reference(RunDirectory& run, const fs::path& dir) {
  const fs::path reference_path = dir / run_layout::reference;
  if (!fs::exists(reference_path))
    throw InputError(reference_path.string() + ": missing (the reference points of the run)");
  run.reference = read_snapshot(reference_path.string());
  const std::string reference_file = reference_path.string();
  if (static_cast<std::int64_t>(run.reference.point_count) != run.info.points)
    throw InputError(reference_file + ": holds " + std::to_string(run.reference.point_count) +
                     " points but run_info.json says " + std::to_string(run.info.points));
  if (run.reference.dimension != run.info.dimension)
    throw InputError(reference_file + ": dimension " + std::to_string(run.reference.dimension) +
                     " differs from run_info.json (" + std::to_string(run.info.dimension) + ")");
  const std::pair<const char*, int> needed[] = {{"position", 3}, {"volume", 1}, {"region", 1}, {"boundary_id", 1}};
  for (const auto& [name, components] : needed) {
    const SnapshotField* field = run.reference.find(name);
    if (!field)
      throw InputError(reference_file + ": field '" + name +
                       "' is missing (expected position, volume, "
                       "region, boundary_id)");
    if (field->components != components)
      throw InputError(reference_file + ": field '" + name + "' has " + std::to_string(field->components) +
                       " components (expected " + std::to_string(components) + ")");
  }
}

}  // namespace

RunDirectory open_run_directory(const std::string& path, bool allow_unfinished) {
  RunDirectory run;
  run.path = path;
  const fs::path dir(path);
  const fs::path info_path = run_info_path(path);
  run.info = read_run_info(info_path.string());
  check_run_status(run, info_path, allow_unfinished);
  check_snapshot_list(run.info, dir, info_path);
  read_resolved_scene(run, dir);
  read_reference(run, dir);
  return run;
}

}  // namespace mppm::post
