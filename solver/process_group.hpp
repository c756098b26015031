// The processes of a run (docs/theory.md section 13): one in a plain run, the ranks of
// MPI_COMM_WORLD under mpirun. The solver asks it for the global sums and agreements it needs; the
// sums go through exact accumulators merged by integer addition (exact_sum.hpp), never MPI_SUM on
// doubles, so every process gets the same bits for any number of processes. A plain run's group
// makes no MPI call.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "solver/exact_sum.hpp"

namespace mppm::solver {

class ProcessGroup {
 public:
  // One process, no MPI.
  static ProcessGroup single() { return ProcessGroup(); }
  // Every process of MPI_COMM_WORLD (MPI initialized: MpiSession).
  static ProcessGroup world();

  int rank() const { return rank_; }
  // The collective calls (sums, agreements, gathers, broadcasts) made through this group so far
  // and the wall time spent in them (waiting for the slowest process included): the benchmark's
  // reduction timer.
  struct Reductions {
    std::int64_t calls = 0;
    double seconds = 0.0;
  };
  const Reductions& reductions() const { return reductions_; }
  int size() const { return size_; }
  bool distributed() const { return distributed_; }

  // The sums over all processes of each accumulator, rounded once: the same on every process.
  std::vector<double> sum(std::span<const ExactSum> local) const;
  double sum(const ExactSum& local) const { return sum(std::span<const ExactSum>(&local, 1))[0]; }
  // True on every process when it is true on any (a stop or a refusal decided anywhere).
  bool any(bool local) const;
  // The smallest of the processes' values, and their total (integers: exact).
  std::int64_t lowest(std::int64_t local) const;
  std::int64_t total(std::int64_t local) const;
  // The largest of the processes' values (a maximum is exact: the same bits in any order).
  double highest(double local) const;
  // Every process's value, in rank order, on every process.
  std::vector<std::int64_t> gather(std::int64_t local) const;
  // Every process's list, in rank order, on every process.
  std::vector<std::vector<std::int64_t>> gather(std::span<const std::int64_t> local) const;
  // `text` of process `root`, on every process.
  std::string broadcast(const std::string& text, int root) const;
  // The processes of the group that share this one's machine (and so its memory); 1 for one process.
  int processes_on_this_machine() const;

 private:
  ProcessGroup() = default;
  int rank_ = 0;
  int size_ = 1;
  bool distributed_ = false;
  mutable Reductions reductions_;
  class Timed;  // counts a collective call into reductions_
};

// MPI for the life of the object (MPI_Init_thread with funneled threads: only the thread that
// started OpenMP's parallel regions calls MPI), or nothing when MPI is already initialized.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

 private:
  bool owns_ = false;
};

}  // namespace mppm::solver
