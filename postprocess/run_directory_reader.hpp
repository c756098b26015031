// Opening a run directory written by mppm-solve (common/run_directory.hpp, docs/stages.md) and
// checking it before any output is written: run_info.json, the resolved scene, the reference
// points and the list of snapshots. Every problem is an InputError naming the file.
#pragma once
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <vector>

#include "common/snapshot_file.hpp"

namespace mppm::post {

struct SnapshotEntry {
  std::string path;  // absolute or relative to the current directory
  std::int64_t step = 0;
  double time = 0.0;
};

struct RunInfo {
  std::string status;  // "completed" | "numerical_failure" | "interrupted" | "running"
  std::string message;
  std::int64_t points = 0, bonds = 0, steps = 0, detached_points = 0;
  double time_s = 0.0, wall_seconds = 0.0;
  double time_step_s = 0.0;
  int threads = 0;
  int dimension = 0;
  std::vector<std::string> effects;
  std::vector<SnapshotEntry> snapshots;
};

struct RunDirectory {
  std::string path;
  RunInfo info;
  YAML::Node scene;                // scene.resolved.yaml as written by the solver
  double spacing = 0.0;            // dx [m]
  double horizon = 0.0;            // delta [m]
  double thickness = 1.0;          // 2-D thickness [m]
  Snapshot reference;              // position(3), volume, region, boundary_id
  std::vector<std::string> notes;  // things the user should know (partial run, ...)
};

// Throws InputError. `allow_unfinished` accepts a run whose status is still "running" (a
// crashed or live run) and uses the snapshots listed so far.
RunDirectory open_run_directory(const std::string& path, bool allow_unfinished);

// run_info.json alone (tests, tools).
RunInfo read_run_info(const std::string& path);

}  // namespace mppm::post
