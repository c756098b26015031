// The fields a snapshot can hold, computed from the model's state on demand (docs/stages.md
// output.fields): only fields the run has are written; the others are reported once.
#pragma once
#include <string>
#include <vector>

#include "common/snapshot_file.hpp"
#include "solver/model.hpp"

namespace mppm::solver {

// Field names this run can write (depends on the effects).
std::vector<std::string> available_fields(const Model& model);

// The requested fields that are available (unknown ones are skipped), computed from the model's
// state while they are written (write_snapshot of common/snapshot_file.hpp): the model must not
// change before then. The strain and wryness are those of the last force evaluation.
std::vector<SnapshotFieldSource> snapshot_sources(const Model& model, const std::vector<std::string>& fields);

// The same fields assembled in memory.
Snapshot make_snapshot(const Model& model, const std::vector<std::string>& fields, std::int64_t step, double time);

}  // namespace mppm::solver
