// The halo exchange over MPI (halo_exchange.hpp).
#include "solver/halo_exchange.hpp"

#include <mpi.h>

#include <algorithm>
#include <climits>
#include <map>
#include <stdexcept>
#include <string>

#include "solver/parallel_policy.hpp"

namespace mppm::solver {

namespace {

int as_count(std::size_t n) {
  if (n > static_cast<std::size_t>(INT_MAX))
    throw std::length_error("halo exchange: " + std::to_string(n) + " values exceed one MPI message");
  return static_cast<int>(n);
}

// Tells every owner which of its points this process holds as ghosts: returns, per process, the
// global ids that process asked this one for.
std::vector<std::vector<std::int64_t>> exchange_requests(const std::vector<std::vector<std::int64_t>>& asked) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<int> send_count(static_cast<std::size_t>(size)), receive_count(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r)
    send_count[static_cast<std::size_t>(r)] = as_count(asked[static_cast<std::size_t>(r)].size());
  MPI_Alltoall(send_count.data(), 1, MPI_INT, receive_count.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> send_offset(static_cast<std::size_t>(size), 0), receive_offset(static_cast<std::size_t>(size), 0);
  std::vector<std::int64_t> send_ids;
  std::size_t receive_total = 0;
  for (int r = 0; r < size; ++r) {
    const auto k = static_cast<std::size_t>(r);
    send_offset[k] = as_count(send_ids.size());
    send_ids.insert(send_ids.end(), asked[k].begin(), asked[k].end());
    receive_offset[k] = as_count(receive_total);
    receive_total += static_cast<std::size_t>(receive_count[k]);
  }
  std::vector<std::int64_t> receive_ids(receive_total);
  MPI_Alltoallv(send_ids.data(), send_count.data(), send_offset.data(), MPI_INT64_T, receive_ids.data(),
                receive_count.data(), receive_offset.data(), MPI_INT64_T, MPI_COMM_WORLD);
  std::vector<std::vector<std::int64_t>> requested(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) {
    const auto k = static_cast<std::size_t>(r);
    const auto first = receive_ids.begin() + receive_offset[k];
    requested[k].assign(first, first + receive_count[k]);
  }
  return requested;
}

// Packs (`pack`: rows[k] of `values` to row k of `buffer`) or unpacks (the reverse) `c` values per
// point, on every thread when there are many: each row is its own, so the threads write apart.
void copy_rows(const std::vector<std::size_t>& rows, std::vector<double>& values, std::vector<double>& buffer,
               std::size_t c, bool pack) {
  const auto n = static_cast<std::int64_t>(rows.size());
#pragma omp parallel for schedule(static) if (thread_point_loop(rows.size()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto k = static_cast<std::size_t>(s);
    if (pack)
      std::copy_n(&values[rows[k] * c], c, &buffer[k * c]);
    else
      std::copy_n(&buffer[k * c], c, &values[rows[k] * c]);
  }
}

}  // namespace

HaloExchange::HaloExchange(const LocalPoints& local, std::span<const std::int32_t> part_of) {
  int size = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // The ghosts by owner, in ascending global id (the order of the local ghosts).
  std::vector<std::vector<std::int64_t>> asked(static_cast<std::size_t>(size));
  std::map<int, Link> links;
  for (std::size_t k = local.owned; k < local.global_id.size(); ++k) {
    const std::int64_t id = local.global_id[k];
    const int owner = part_of[static_cast<std::size_t>(id)];
    if (owner == rank || owner < 0 || owner >= size)
      throw std::logic_error("halo exchange: ghost " + std::to_string(id) + " has owner " + std::to_string(owner));
    asked[static_cast<std::size_t>(owner)].push_back(id);
    links[owner].rank = owner;
    links[owner].receive.push_back(k);
  }
  const std::vector<std::vector<std::int64_t>> requested = exchange_requests(asked);
  const auto owned_first = local.global_id.begin();
  const auto owned_last = local.global_id.begin() + static_cast<std::ptrdiff_t>(local.owned);
  for (int r = 0; r < size; ++r) {
    for (const std::int64_t id : requested[static_cast<std::size_t>(r)]) {
      const auto it = std::lower_bound(owned_first, owned_last, id);
      if (it == owned_last || *it != id)
        throw std::logic_error("halo exchange: process " + std::to_string(r) + " asked for point " +
                               std::to_string(id) + ", which this process does not own");
      links[r].rank = r;
      links[r].send.push_back(static_cast<std::size_t>(it - owned_first));
    }
  }
  for (auto& [r, link] : links) links_.push_back(std::move(link));
  owned_ = local.owned;
  ghost_slot_.resize(local.global_id.size() - local.owned);
  for (std::size_t l = 0; l < links_.size(); ++l)
    for (std::size_t k = 0; k < links_[l].receive.size(); ++k) ghost_slot_[links_[l].receive[k] - owned_] = {l, k};
}

void HaloExchange::update_ghosts(std::vector<double>& values, int components) const {
  begin_update(values, components);
  finish_updates();
}

void HaloExchange::begin_update(std::vector<double>& values, int components) const {
  const double start = MPI_Wtime();
  if (begun_ == 0) requests_.clear();
  if (begun_ == fields_.size()) fields_.emplace_back();
  Field& field = fields_[begun_];
  // One tag per field in flight, 23 on: below the snapshots' (41, 42).
  if (begun_ >= 16) throw std::logic_error("halo exchange: more than 16 fields begun at once");
  const int tag = 23 + static_cast<int>(begun_);
  ++begun_;
  field.values = &values;
  field.components = static_cast<std::size_t>(components);
  field.send.resize(links_.size());
  field.receive.resize(links_.size());
  const std::size_t c = field.components;
  for (std::size_t l = 0; l < links_.size(); ++l) {
    std::vector<double>& in = field.receive[l];
    in.resize(links_[l].receive.size() * c);
    if (in.empty()) continue;
    requests_.emplace_back();
    MPI_Irecv(in.data(), as_count(in.size()), MPI_DOUBLE, links_[l].rank, tag, MPI_COMM_WORLD, &requests_.back());
  }
  for (std::size_t l = 0; l < links_.size(); ++l) {
    std::vector<double>& out = field.send[l];
    out.resize(links_[l].send.size() * c);
    if (out.empty()) continue;
    copy_rows(links_[l].send, values, out, c, true);
    traffic_.values_sent += static_cast<std::int64_t>(out.size());
    ++traffic_.messages_sent;
    requests_.emplace_back();
    MPI_Isend(out.data(), as_count(out.size()), MPI_DOUBLE, links_[l].rank, tag, MPI_COMM_WORLD, &requests_.back());
  }
  const double packed = MPI_Wtime() - start;
  traffic_.pack_seconds += packed;
  traffic_.seconds += packed;
}

void HaloExchange::advance_transfers() const {
  if (requests_.empty()) return;
  const double start = MPI_Wtime();
  int all_done = 0;  // completed requests become MPI_REQUEST_NULL, which finish_updates' wait skips
  MPI_Testall(static_cast<int>(requests_.size()), requests_.data(), &all_done, MPI_STATUSES_IGNORE);
  const double spent = MPI_Wtime() - start;
  traffic_.wait_seconds += spent;
  traffic_.seconds += spent;
}

void HaloExchange::finish_updates() const {
  const double wait_start = MPI_Wtime();
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  const double unpack_start = MPI_Wtime();
  for (std::size_t k = 0; k < begun_; ++k)
    for (std::size_t l = 0; l < links_.size(); ++l)
      copy_rows(links_[l].receive, *fields_[k].values, fields_[k].receive[l], fields_[k].components, false);
  const double end = MPI_Wtime();
  traffic_.exchanges += static_cast<std::int64_t>(begun_);
  traffic_.wait_seconds += unpack_start - wait_start;
  traffic_.unpack_seconds += end - unpack_start;
  traffic_.seconds += end - wait_start;
  begun_ = 0;
  requests_.clear();
}

std::vector<PointNote> HaloExchange::notify_owners(std::span<const PointNote> about_ghosts) const {
  // Each note travels as (the ghost's place in the owner's send list, value); every link carries a
  // message, empty or not, so that each process knows how many to wait for.
  constexpr int kTag = 17;  // apart from the fields' tags (23 on)
  std::vector<std::vector<std::int64_t>> out(links_.size());
  for (const PointNote& note : about_ghosts) {
    const auto [l, k] = ghost_slot_.at(note.point - owned_);
    out[l].push_back(static_cast<std::int64_t>(k));
    out[l].push_back(note.value);
  }
  std::vector<MPI_Request> requests(links_.size());
  for (std::size_t l = 0; l < links_.size(); ++l)
    MPI_Isend(out[l].data(), as_count(out[l].size()), MPI_INT64_T, links_[l].rank, kTag, MPI_COMM_WORLD, &requests[l]);
  std::vector<PointNote> received;
  std::vector<std::int64_t> in;
  for (std::size_t l = 0; l < links_.size(); ++l) {
    MPI_Status status;
    MPI_Probe(links_[l].rank, kTag, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_INT64_T, &count);
    in.resize(static_cast<std::size_t>(count));
    MPI_Recv(in.data(), count, MPI_INT64_T, links_[l].rank, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    for (std::size_t m = 0; m + 1 < in.size(); m += 2)
      received.push_back({links_[l].send.at(static_cast<std::size_t>(in[m])), in[m + 1]});
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return received;
}

std::size_t HaloExchange::points_sent() const {
  std::size_t n = 0;
  for (const Link& l : links_) n += l.send.size();
  return n;
}

std::size_t HaloExchange::points_received() const {
  std::size_t n = 0;
  for (const Link& l : links_) n += l.receive.size();
  return n;
}

}  // namespace mppm::solver
