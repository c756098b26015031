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
// The same for any fields of the owned points (`local`: their values by local index, e.g. the
// reference configuration's).
void with_gathered_fields(const PointData& points, const std::vector<SnapshotFieldSource>& local,
                          std::span<const std::int32_t> part_of, const ProcessGroup& group, const GatheredWrite& write);

// The process of each global row in [begin, end), into out (called on the first process, once per
// chunk).
using RowOwners = std::function<void(std::int64_t begin, std::int64_t end, std::int32_t* out)>;

// Rows of an array spread over the processes, each row on one process: a point's, a row of the
// points some array holds (the integrator's tracked points), or a bond's (BondRows).
struct DistributedRows {
  std::span<const std::int64_t> local_ids;  // the global index of each of this process's rows, ascending
  RowOwners owners;
};

// The owners of rows listed one per row (`owner`: the process of every global row).
RowOwners owners_listed(std::span<const std::int32_t> owner);

// Fields over one set of rows: `local` gives this process's rows by local index.
struct GatheredRowSet {
  DistributedRows rows;
  std::vector<SnapshotFieldSource> local;
};

// The sources of every set's fields over all its global rows, in order, for the first process.
using GatheredSetsWrite = std::function<void(const std::vector<std::vector<SnapshotFieldSource>>& whole)>;

// Collective, as with_gathered_fields, for several sets of rows at once (a checkpoint: per point
// and per tracked point).
void with_gathered_row_sets(const std::vector<GatheredRowSet>& sets, const ProcessGroup& group,
                            const GatheredSetsWrite& write);

}  // namespace mppm::solver
