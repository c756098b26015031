// The snapshots of a distributed run (docs/theory.md section 13): the first process writes the file
// of the one-process run (points in global-id order, the same bytes), streamed chunk by chunk as
// the snapshot writer asks for values (common/snapshot_file.hpp), and asks the owners of each
// chunk's points for theirs; the other processes answer meanwhile. No process holds a whole field:
// the first holds one chunk of every process's values at a time.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "common/snapshot_file.hpp"
#include "solver/model.hpp"
#include "solver/process_group.hpp"

namespace mppm::solver {

// The whole model's field sources and its point count, for the first process's writer.
using GatheredWrite = std::function<void(const std::vector<SnapshotFieldSource>& sources, std::uint64_t points)>;

// Collective: every process calls it with its local model (`part_of`: the process of every point of
// the whole cloud). `write` runs on the first process only; the others answer its requests until
// it returns (or throws: the exception is rethrown there, after the others are released).
void with_gathered_fields(const Model& model, const std::vector<std::string>& fields,
                          std::span<const std::int32_t> part_of, const ProcessGroup& group, const GatheredWrite& write);
// The same for any fields of the local points (`local`: their values by local index, e.g. the
// reference configuration's).
void with_gathered_fields(const PointData& points, const std::vector<SnapshotFieldSource>& local,
                          std::span<const std::int32_t> part_of, const ProcessGroup& group, const GatheredWrite& write);

}  // namespace mppm::solver
