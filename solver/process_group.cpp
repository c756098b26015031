// The process group over MPI (process_group.hpp).
#include "solver/process_group.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <stdexcept>

namespace mppm::solver {

// Adds the wall time of its scope to a distributed group's reduction timer.
class ProcessGroup::Timed {
 public:
  explicit Timed(const ProcessGroup& g)
      : g_(g), start_(g.distributed_ ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{}) {}
  ~Timed() {
    if (!g_.distributed_) return;
    ++g_.reductions_.calls;
    g_.reductions_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;

 private:
  const ProcessGroup& g_;
  std::chrono::steady_clock::time_point start_;
};

ProcessGroup ProcessGroup::world() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) throw std::logic_error("ProcessGroup::world: MPI is not initialized");
  ProcessGroup g;
  MPI_Comm_rank(MPI_COMM_WORLD, &g.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &g.size_);
  g.distributed_ = true;
  return g;
}

std::vector<double> ProcessGroup::sum(std::span<const ExactSum> local) const {
  const Timed timed(*this);
  std::vector<double> out(local.size());
  if (!distributed_) {
    for (std::size_t k = 0; k < local.size(); ++k) out[k] = local[k].value();
    return out;
  }
  // Integer addition of the normalized digits is exact and does not depend on the order in which
  // MPI combines the processes' contributions.
  constexpr auto words = static_cast<std::size_t>(ExactSum::kWireWords);
  std::vector<std::int64_t> mine(local.size() * words), all(local.size() * words);
  for (std::size_t k = 0; k < local.size(); ++k) {
    const ExactSum::Wire w = local[k].wire();
    std::copy(w.begin(), w.end(), mine.begin() + static_cast<std::ptrdiff_t>(k * words));
  }
  MPI_Allreduce(mine.data(), all.data(), static_cast<int>(mine.size()), MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  for (std::size_t k = 0; k < local.size(); ++k)
    out[k] =
        ExactSum::from_wire(std::span<const std::int64_t, ExactSum::kWireWords>(all.data() + k * words, words)).value();
  return out;
}

bool ProcessGroup::any(bool local) const {
  const Timed timed(*this);
  if (!distributed_) return local;
  int mine = local ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return all != 0;
}

namespace {

// An integer combined over every process by `op` (exact, whatever the order).
std::int64_t all_reduced(std::int64_t local, MPI_Op op) {
  std::int64_t all = 0;
  MPI_Allreduce(&local, &all, 1, MPI_INT64_T, op, MPI_COMM_WORLD);
  return all;
}

}  // namespace

std::int64_t ProcessGroup::lowest(std::int64_t local) const {
  const Timed timed(*this);
  return distributed_ ? all_reduced(local, MPI_MIN) : local;
}

double ProcessGroup::highest(double local) const {
  const Timed timed(*this);
  double out = local;
  if (distributed_) MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

std::int64_t ProcessGroup::total(std::int64_t local) const {
  const Timed timed(*this);
  return distributed_ ? all_reduced(local, MPI_SUM) : local;
}

std::vector<std::int64_t> ProcessGroup::gather(std::int64_t local) const {
  const Timed timed(*this);
  std::vector<std::int64_t> all(static_cast<std::size_t>(size_), local);
  if (distributed_) MPI_Allgather(&local, 1, MPI_INT64_T, all.data(), 1, MPI_INT64_T, MPI_COMM_WORLD);
  return all;
}

std::vector<std::vector<std::int64_t>> ProcessGroup::gather(std::span<const std::int64_t> local) const {
  const Timed timed(*this);
  if (!distributed_) return {std::vector<std::int64_t>(local.begin(), local.end())};
  std::vector<std::int64_t> sizes(static_cast<std::size_t>(size_));
  const auto length = static_cast<std::int64_t>(local.size());
  MPI_Allgather(&length, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, MPI_COMM_WORLD);
  std::vector<int> counts(sizes.begin(), sizes.end()), offsets(sizes.size(), 0);
  for (std::size_t r = 1; r < sizes.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<std::int64_t> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(local.data(), static_cast<int>(local.size()), MPI_INT64_T, all.data(), counts.data(), offsets.data(),
                 MPI_INT64_T, MPI_COMM_WORLD);
  std::vector<std::vector<std::int64_t>> out(sizes.size());
  for (std::size_t r = 0; r < sizes.size(); ++r)
    out[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
  return out;
}

std::string ProcessGroup::broadcast(const std::string& text, int root) const {
  const Timed timed(*this);
  if (!distributed_) return text;
  std::int64_t length = rank_ == root ? static_cast<std::int64_t>(text.size()) : 0;
  MPI_Bcast(&length, 1, MPI_INT64_T, root, MPI_COMM_WORLD);
  std::string out = rank_ == root ? text : std::string(static_cast<std::size_t>(length), '\0');
  MPI_Bcast(out.data(), static_cast<int>(length), MPI_CHAR, root, MPI_COMM_WORLD);
  return out;
}

int ProcessGroup::processes_on_this_machine() const {
  if (!distributed_) return 1;
  MPI_Comm machine = MPI_COMM_NULL;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &machine);
  int size = 1;
  MPI_Comm_size(machine, &size);
  MPI_Comm_free(&machine);
  return size;
}

MpiSession::MpiSession(int& argc, char**& argv) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  owns_ = true;
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw std::runtime_error("MPI does not support threads calling it from the main thread (MPI_THREAD_FUNNELED)");
  }
}

MpiSession::~MpiSession() {
  if (owns_) MPI_Finalize();
}

}  // namespace mppm::solver
