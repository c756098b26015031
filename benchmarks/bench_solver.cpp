// mppm-bench-solver: throughput of the solver in bond updates per second (one bond update = one
// bond visited by both passes of the force kernel). Kernel alone (force evaluation) and whole
// steps (kernel + integrator + boundary work bookkeeping) and a whole mppm-solve run (start-up,
// energy rows, snapshots and files included), 2-D (200 x 80 points, horizon factor
// 4.05, the crack-branching lattice) and 3-D, micropolar on and off, 1 and 2 threads.
// Not a test: it prints figures for the README.
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "solver/critical_time_step.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/model.hpp"
#include "solver/solve_run.hpp"

using namespace mppm;
using namespace mppm::solver;

namespace {

PointCloud lattice(int d, std::array<int, 3> n, double dx) {
  PointCloud c;
  c.dimension = d;
  c.spacing = dx;
  const int nz = d == 2 ? 1 : n[2];
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        c.x.push_back((i + 0.5) * dx);
        c.y.push_back((j + 0.5) * dx);
        c.z.push_back(d == 3 ? (k + 0.5) * dx : 0.0);
        c.volume.push_back(d == 2 ? dx * dx * 1e-3 : dx * dx * dx);
        c.region.push_back(0);
        c.boundary_id.push_back(0);
      }
  return c;
}

Model model(int d, std::array<int, 3> n, double factor, bool micropolar) {
  const double dx = 5e-4;
  ModelOptions o;
  CosseratConstants& c = o.constants;
  c.dimension = d;
  c.micropolar = micropolar;
  c.lambda = 14e9;
  c.mu = 14e9;
  c.mu_c = micropolar ? 14e9 / 3 : 0.0;
  c.a2 = d == 3 ? 56e3 : 0.0;
  c.a3 = d == 2 ? 56e3 : 0.0;
  c.bending_modulus = 56e3;
  c.density = 0.95 * 2650;
  c.micro_inertia = 0.5 * 3.14159265358979 * c.density * 4e-6;
  c.stabilization = 0.1;
  o.effects.micropolar = micropolar;
  o.horizon = factor * dx;
  o.spacing = dx;
  Model m = build_model(lattice(d, n, dx), o);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> g(-1e-7, 1e-7);
  for (auto& u : m.points.displacement) u = g(rng);
  for (auto& w : m.points.rotation) w = 1e3 * g(rng);
  return m;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void run(const char* label, int d, std::array<int, 3> n, double factor, bool micropolar, int repeats) {
  Model m = model(d, n, factor, micropolar);
  const double bonds = static_cast<double>(m.bonds.bond_count());
  std::printf("%s: %zu points, %.0f bonds (%.1f per point), micropolar %s\n", label, m.points.owned, bonds,
              bonds / static_cast<double>(m.points.owned), micropolar ? "on" : "off");
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    m.compute_internal_forces();  // warm up
    auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r) m.compute_internal_forces();
    const double kernel = seconds_since(t0) / repeats;
    BoundaryConditions none(m.points);
    ExplicitDynamics dynamics(m, none, 1e-9);
    dynamics.initialize();
    t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r) dynamics.step(false);
    const double step = seconds_since(t0) / repeats;
    std::printf("  threads %d: kernel %.3f ms = %.1f M bond updates/s; whole step %.3f ms = %.1f M bond updates/s\n",
                threads, 1e3 * kernel, bonds / kernel / 1e6, 1e3 * step, bonds / step / 1e6);
  }
}

// A whole run through the library entry point of mppm-solve: start-up (families, shape tensors,
// critical step), 200 steps with energy rows every step, snapshots, files. Crack-branching
// material and lattice (micropolar), ramped tractions on the top and bottom rows.
void whole_run(int threads) {
  omp_set_num_threads(threads);
  const double dx = 5e-4;
  PointCloud cloud = lattice(2, {200, 80, 1}, dx);
  cloud.horizon = 4.05 * dx;
  std::int64_t top = 0, bottom = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    cloud.normal_x.push_back(0.0);
    cloud.normal_z.push_back(0.0);
    cloud.normal_y.push_back(0.0);
    if (cloud.y[i] > 79 * dx) {
      cloud.boundary_id[i] = 1;
      ++top;
    }
    if (cloud.y[i] < dx) {
      cloud.boundary_id[i] = 2;
      ++bottom;
    }
  }
  cloud.boundaries = {BoundaryInfo{"top", "traction", 0.1 * 1e-3, top, "", 0.0},
                      BoundaryInfo{"bottom", "traction", 0.1 * 1e-3, bottom, "", 0.0}};
  Scene s;
  s.path = "bench.yaml";
  s.dimension = 2;
  s.thickness = 1e-3;
  s.geometry.spacing = dx;
  s.geometry.horizon_factor = 4.05;
  s.material.density = 2650;
  s.material.solid_fraction = 0.95;
  s.material.lambda = s.material.mu = 14e9;
  s.material.mu_c = 14e9 / 3;
  s.material.couple_moduli = {0, 0, 56e3};
  s.material.length_scale = 2e-3;
  s.effects.micropolar = true;
  for (int k = 0; k < 2; ++k) {
    BoundaryCondition bc;
    bc.name = k == 0 ? "top" : "bottom";
    bc.type = BoundaryType::traction;
    bc.value.times = {0.0, 6.25e-6};
    bc.value.values = {{0.0, 0.0}, {0.0, k == 0 ? 8e6 : -8e6}};
    s.boundary_conditions.push_back(bc);
  }
  s.time.step = 2.5e-8;
  s.time.end = 200 * 2.5e-8;
  s.output.interval = s.time.end / 4;
  s.output.fields = {"displacement", "rotation"};
  solver::SolveOptions o;
  o.run_directory = (std::filesystem::temp_directory_path() / "mppm-bench-solver-run").string();
  o.force = true;
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = solver::solve(s, cloud, o);
  const double wall = seconds_since(t0);
  const Model m = [&] {
    ModelOptions mo;
    mo.constants = cosserat_constants(s);
    mo.effects = s.effects;
    mo.horizon = s.geometry.horizon();
    mo.spacing = dx;
    return build_model(cloud, mo);
  }();
  const double updates = static_cast<double>(m.bonds.bond_count()) * static_cast<double>(r.steps);
  std::printf("  whole run, threads %d: %lld steps in %.2f s (start-up and output included) = %.1f M bond updates/s\n",
              threads, static_cast<long long>(r.steps), wall, updates / wall / 1e6);
  std::filesystem::remove_all(o.run_directory);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 20;
  run("2-D 200 x 80, horizon factor 4.05", 2, {200, 80, 1}, 4.05, true, repeats);
  std::printf("2-D 200 x 80, horizon factor 4.05, micropolar, mppm-solve run of 200 steps:\n");
  whole_run(1);
  whole_run(2);
  run("2-D 200 x 80, horizon factor 4.05", 2, {200, 80, 1}, 4.05, false, repeats);
  run("3-D 40 x 40 x 40, horizon factor 2.05", 3, {40, 40, 40}, 2.05, true, std::max(1, repeats / 4));
  run("3-D 40 x 40 x 40, horizon factor 2.05", 3, {40, 40, 40}, 2.05, false, std::max(1, repeats / 4));
  return 0;
}
