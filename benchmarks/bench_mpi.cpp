// mppm-bench-mpi: the distributed integrator's throughput (bond updates per second) and its halo
// traffic, under mpirun with any number of processes and threads (docs/theory.md section 13): the
// partition, the local models and their ghosts, then timed steps without energy rows. Prints one
// CSV row (process 0): the case, processes, threads, points, bonds, steps, the loop's wall time (the
// slowest process), bond updates per second, the halo exchanges' wall time (the slowest process) and
// share, the values and messages sent per step (all processes), the ghosts and the partition's
// imbalance (the heaviest process's bonds over the mean), and per step the timers of the slowest
// process in milliseconds: packing, waiting and unpacking in the halo exchanges, the collective
// calls (sums and agreements) and their number, and the rest of the step (the kernel and the
// integrator). Not a test: workflows/benchmarks/run_mpi.py
// runs it and writes results_mpi.md.
//
//   mpirun -np 2 mppm-bench-mpi plate|plate-wide|block [STEPS]
#include <mpi.h>
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include "solver/boundary_conditions.hpp"
#include "solver/critical_time_step.hpp"
#include "solver/distributed_model.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/halo_exchange.hpp"
#include "solver/horizon_search.hpp"
#include "solver/local_points.hpp"
#include "solver/model.hpp"
#include "solver/process_group.hpp"
#include "tests/verification/problems/generic_scene.hpp"
#include "tests/verification/problems/periodic_lattice.hpp"

using namespace mppm;
using namespace mppm::solver;

namespace {

struct Case {
  std::string name;
  int dimension;
  std::array<int, 3> n;
  double horizon_factor;
};

// The crack-branching plate's lattice (200 x 80, horizon 4.05 dx), the same twice as long, and the
// 3-D benchmark block (60^3, horizon 2.05 dx; workflows/benchmarks/scenes/block60.geo), micro-polar.
Case case_named(const std::string& name) {
  if (name == "plate") return {name, 2, {200, 80, 1}, 4.05};
  if (name == "plate-wide") return {name, 2, {400, 80, 1}, 4.05};  // weak scaling: twice the plate
  if (name == "block") return {name, 3, {60, 60, 60}, 2.05};
  std::fprintf(stderr, "mppm-bench-mpi: unknown case '%s' (expected plate, plate-wide or block)\n", name.c_str());
  std::exit(2);
}

double max_over_processes(double local) {
  double out = 0.0;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

std::int64_t total_over_processes(std::int64_t local) {
  std::int64_t out = 0;
  MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  const ProcessGroup group = ProcessGroup::world();
  const Case k = case_named(argc > 1 ? argv[1] : "plate");
  const int steps = argc > 2 ? std::atoi(argv[2]) : 200;
  const double dx = 5e-4;
  const Scene scene = verification::make_scene(k.dimension, true, dx, k.horizon_factor);
  const PointCloud cloud = verification::make_lattice(k.dimension, k.n, dx, scene.thickness);
  const ModelOptions o = model_options(scene);

  DistributedModel distributed = build_distributed_model(cloud, o, group);
  Model& model = distributed.model;
  const LocalPoints& local = distributed.local;
  BoundaryConditions conditions(scene, cloud, "in-memory lattice");
  conditions.keep_owned(local);
  ExplicitDynamics dynamics(model, conditions, 0.8 * critical_time_step(model).step);
  for (std::size_t i = 0; i < model.points.owned * static_cast<std::size_t>(k.dimension); ++i)
    model.points.velocity[i] = 1e-3 * static_cast<double>(i % 7);
  dynamics.initialize();

  const HaloExchange::Traffic before = distributed.halo->traffic();
  const ProcessGroup::Reductions reductions_before = group.reductions();
  MPI_Barrier(MPI_COMM_WORLD);
  const double start = MPI_Wtime();
  for (int s = 0; s < steps; ++s) dynamics.step(false);
  const double loop = max_over_processes(MPI_Wtime() - start);
  const HaloExchange::Traffic& after = distributed.halo->traffic();
  const double halo_seconds = max_over_processes(after.seconds - before.seconds);
  const double reduction_seconds = group.reductions().seconds - reductions_before.seconds;
  const double reductions_per_step =
      static_cast<double>(group.reductions().calls - reductions_before.calls) / static_cast<double>(steps);
  // Per step, in ms, of the slowest process for each timer.
  auto per_step_ms = [&](double seconds) { return 1e3 * max_over_processes(seconds) / static_cast<double>(steps); };
  const double pack_ms = per_step_ms(after.pack_seconds - before.pack_seconds);
  const double wait_ms = per_step_ms(after.wait_seconds - before.wait_seconds);
  const double unpack_ms = per_step_ms(after.unpack_seconds - before.unpack_seconds);
  const double reduction_ms = per_step_ms(reduction_seconds);
  const std::int64_t values = total_over_processes(after.values_sent - before.values_sent);
  const std::int64_t messages = total_over_processes(after.messages_sent - before.messages_sent);
  const double rest_ms = 1e3 * loop / static_cast<double>(steps) - per_step_ms(after.seconds - before.seconds) -
                         reduction_ms;  // kernel and integrator
  const PartitionSummary partition = summarize_partition(model, group);
  const std::int64_t bonds = std::accumulate(partition.bonds.begin(), partition.bonds.end(), std::int64_t{0});
  const std::int64_t ghosts = std::accumulate(partition.ghosts.begin(), partition.ghosts.end(), std::int64_t{0});
  const double imbalance = partition.imbalance;
  if (group.rank() == 0) {
    std::printf(
        "case,processes,threads,points,bonds,steps,loop_seconds,bond_updates_per_second,halo_seconds,halo_share,"
        "values_sent_per_step,messages_per_step,ghosts,imbalance,pack_ms,wait_ms,unpack_ms,reduction_ms,"
        "reductions_per_step,kernel_and_integrator_ms\n");
    std::printf("%s,%d,%d,%zu,%lld,%d,%.4f,%.4e,%.4f,%.4f,%.1f,%.1f,%lld,%.4f,%.4f,%.4f,%.4f,%.4f,%.1f,%.4f\n",
                k.name.c_str(), group.size(), omp_get_max_threads(), cloud.size(), static_cast<long long>(bonds), steps,
                loop, static_cast<double>(bonds) * steps / loop, halo_seconds, halo_seconds / loop,
                static_cast<double>(values) / steps, static_cast<double>(messages) / steps,
                static_cast<long long>(ghosts), imbalance, pack_ms, wait_ms, unpack_ms, reduction_ms,
                reductions_per_step, rest_ms);
  }
  return 0;
}
