// Gathered snapshot fields (distributed_snapshot.hpp): a request (field, first global id, end) to
// each owner of a chunk's points, its values in ascending global id back, placed by the partition.
#include "solver/distributed_snapshot.hpp"

#include <mpi.h>

#include <algorithm>
#include <array>

#include "solver/snapshot_fields.hpp"

namespace mppm::solver {

namespace {

constexpr int kRequestTag = 41, kValuesTag = 42;
using Request = std::array<std::int64_t, 3>;  // field (-1: done), first global id, end

// The local range of this process's rows whose global indices lie in [first, end) (they ascend).
std::pair<std::size_t, std::size_t> own_range(std::span<const std::int64_t> ids, std::int64_t first, std::int64_t end) {
  return {static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), first) - ids.begin()),
          static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), end) - ids.begin())};
}

// A field of one of the sets, by its index over all sets' fields (the requests' numbering).
struct FieldOfSet {
  std::size_t set, field;
};

std::vector<FieldOfSet> number_fields(const std::vector<GatheredRowSet>& sets) {
  std::vector<FieldOfSet> fields;
  for (std::size_t s = 0; s < sets.size(); ++s)
    for (std::size_t f = 0; f < sets[s].local.size(); ++f) fields.push_back({s, f});
  return fields;
}

// This process's values of field `f` for its rows with global indices in [first, end).
std::vector<double> own_values(const std::vector<GatheredRowSet>& sets, const FieldOfSet& f, std::int64_t first,
                               std::int64_t end) {
  const SnapshotFieldSource& source = sets[f.set].local[f.field];
  const auto [lo, hi] = own_range(sets[f.set].rows.local_ids, first, end);
  std::vector<double> v((hi - lo) * static_cast<std::size_t>(source.components));
  if (hi > lo) source.values(lo, hi - lo, v.data());
  return v;
}

// The other processes: values for each request of the first, until it says done.
void serve(const std::vector<GatheredRowSet>& sets) {
  const std::vector<FieldOfSet> fields = number_fields(sets);
  for (;;) {
    Request r{};
    MPI_Recv(r.data(), 3, MPI_INT64_T, 0, kRequestTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (r[0] < 0) return;
    const std::vector<double> v = own_values(sets, fields[static_cast<std::size_t>(r[0])], r[1], r[2]);
    MPI_Send(v.data(), static_cast<int>(v.size()), MPI_DOUBLE, 0, kValuesTag, MPI_COMM_WORLD);
  }
}

// The first process: chunk [first, first + count) of field f (numbered over all sets), from every
// owner, in global order.
void gather_chunk(const std::vector<GatheredRowSet>& sets, const std::vector<FieldOfSet>& fields, int processes,
                  std::int64_t f, std::uint64_t first, std::uint64_t count, double* out) {
  const FieldOfSet& field = fields[static_cast<std::size_t>(f)];
  const DistributedRows& rows = sets[field.set].rows;
  const auto c = static_cast<std::size_t>(sets[field.set].local[field.field].components);
  const auto begin = static_cast<std::int64_t>(first), end = static_cast<std::int64_t>(first + count);
  std::vector<std::int32_t> owner(count);
  rows.owners(begin, end, owner.data());
  std::vector<std::size_t> expected(static_cast<std::size_t>(processes), 0);
  for (const std::int32_t r : owner) ++expected[static_cast<std::size_t>(r)];
  std::vector<std::vector<double>> received(static_cast<std::size_t>(processes));
  std::vector<MPI_Request> pending;
  const Request request{f, begin, end};
  for (int r = 1; r < processes; ++r) {
    const auto k = static_cast<std::size_t>(r);
    if (expected[k] == 0) continue;
    received[k].resize(expected[k] * c);
    pending.emplace_back();
    MPI_Irecv(received[k].data(), static_cast<int>(received[k].size()), MPI_DOUBLE, r, kValuesTag, MPI_COMM_WORLD,
              &pending.back());
    MPI_Send(request.data(), 3, MPI_INT64_T, r, kRequestTag, MPI_COMM_WORLD);
  }
  received[0] = own_values(sets, field, begin, end);
  MPI_Waitall(static_cast<int>(pending.size()), pending.data(), MPI_STATUSES_IGNORE);
  std::vector<std::size_t> next(static_cast<std::size_t>(processes), 0);
  for (std::int64_t g = begin; g < end; ++g) {
    const auto r = static_cast<std::size_t>(owner[static_cast<std::size_t>(g - begin)]);
    std::copy_n(&received[r][next[r] * c], c, &out[static_cast<std::size_t>(g - begin) * c]);
    ++next[r];
  }
}

}  // namespace

RowOwners owners_listed(std::span<const std::int32_t> owner) {
  return [owner](std::int64_t begin, std::int64_t end, std::int32_t* out) {
    std::copy(owner.begin() + begin, owner.begin() + end, out);
  };
}

void with_gathered_fields(const Model& model, const std::vector<std::string>& fields,
                          std::span<const std::int32_t> part_of, const ProcessGroup& group,
                          const GatheredWrite& write) {
  with_gathered_fields(model.points, snapshot_sources(model, fields), part_of, group, write);
}

void with_gathered_fields(const PointData& points, const std::vector<SnapshotFieldSource>& local,
                          std::span<const std::int32_t> part_of, const ProcessGroup& group,
                          const GatheredWrite& write) {
  const std::span<const std::int64_t> owned(points.global_id.data(), points.owned);
  with_gathered_row_sets(
      {GatheredRowSet{DistributedRows{owned, owners_listed(part_of)}, local}}, group,
      [&](const std::vector<std::vector<SnapshotFieldSource>>& whole) { write(whole[0], part_of.size()); });
}

void with_gathered_row_sets(const std::vector<GatheredRowSet>& sets, const ProcessGroup& group,
                            const GatheredSetsWrite& write) {
  if (group.rank() != 0) {
    serve(sets);
    return;
  }
  const std::vector<FieldOfSet> fields = number_fields(sets);
  std::vector<std::vector<SnapshotFieldSource>> whole(sets.size());
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const SnapshotFieldSource& local = sets[fields[f].set].local[fields[f].field];
    SnapshotFieldSource s;
    s.name = local.name;
    s.components = local.components;
    s.values = [&, f](std::uint64_t first, std::uint64_t count, double* out) {
      gather_chunk(sets, fields, group.size(), static_cast<std::int64_t>(f), first, count, out);
    };
    whole[fields[f].set].push_back(std::move(s));
  }
  auto release_others = [&] {
    const Request done{-1, 0, 0};
    for (int r = 1; r < group.size(); ++r) MPI_Send(done.data(), 3, MPI_INT64_T, r, kRequestTag, MPI_COMM_WORLD);
  };
  try {
    write(whole);
  } catch (...) {
    release_others();
    throw;
  }
  release_others();
}

}  // namespace mppm::solver
