// mppm-bench-checkpoint: the cost of one checkpoint of a large 3-D run (README "Reliability"):
// bytes, seconds to write it (atomic: temporary, fsync, rename) and seconds to read it back and
// restore the state, for a cubic lattice of N^3 points (default N = 100: 1 million points,
// horizon factor 2.05, 30.4 bonds per point), micropolar, elastic and with damage (whose marked
// neighbour lists and bond work make the checkpoint grow with the bonds). The model is built, not run: the
// checkpoint's cost does not depend on the state's values.
// Usage: mppm-bench-checkpoint [N] [DIRECTORY] [REPEATS]. Not a test: it prints figures.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "common/checkpoint_file.hpp"
#include "solver/checkpoint.hpp"
#include "solver/explicit_dynamics.hpp"
#include "solver/model.hpp"

using namespace mppm;
using namespace mppm::solver;

namespace {

PointCloud cube(int n, double dx) {
  PointCloud c;
  c.dimension = 3;
  c.spacing = dx;
  const auto count = static_cast<std::size_t>(n) * n * n;
  c.x.reserve(count);
  c.y.reserve(count);
  c.z.reserve(count);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        c.x.push_back((i + 0.5) * dx);
        c.y.push_back((j + 0.5) * dx);
        c.z.push_back((k + 0.5) * dx);
      }
  c.volume.assign(count, dx * dx * dx);
  c.region.assign(count, 0);
  c.boundary_id.assign(count, 0);
  return c;
}

Model build(const PointCloud& cloud, bool damage) {
  const double dx = cloud.spacing;
  ModelOptions o;
  CosseratConstants& c = o.constants;
  c.dimension = 3;
  c.micropolar = true;
  c.lambda = c.mu = 14e9;
  c.mu_c = 14e9 / 3;
  c.a1 = 0.0;
  c.a2 = 56e3;
  c.a3 = 10e3;
  c.bending_modulus = 56e3;
  c.density = 0.95 * 2650;
  c.micro_inertia = 0.5 * 3.14159265358979 * c.density * 4e-6;
  c.stabilization = 0.1;
  c.critical_bond_work = 1e3;
  o.effects.micropolar = true;
  o.effects.damage = damage;
  o.horizon = 2.05 * dx;
  o.spacing = dx;
  Model m = build_model(cloud, o);
  // Values of a moving body (the checkpoint writes the arrays' bytes whatever they hold).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> g(-1e-7, 1e-7);
  for (auto* v : {&m.points.displacement, &m.points.velocity, &m.points.rotation, &m.points.spin})
    for (auto& x : *v) x = g(rng);
  return m;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void measure(const char* label, const PointCloud& cloud, bool damage, const std::string& directory, int repeats) {
  auto t0 = std::chrono::steady_clock::now();
  Model m = build(cloud, damage);
  const double build_seconds = seconds_since(t0);
  BoundaryConditions none(m.points);
  ExplicitDynamics dynamics(m, none, 1e-9);
  RunLoopState loop;
  loop.points_file = "bench";
  loop.time_step = 1e-9;
  const RunIdentity identity{1, 2};
  const std::string path = directory + "/state.ckpt";
  double write_min = 1e300, write_max = 0.0, read_min = 1e300, read_max = 0.0;
  for (int r = 0; r < repeats; ++r) {
    t0 = std::chrono::steady_clock::now();
    write_checkpoint(path, identity, m, dynamics, loop);
    const double w = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const CheckpointFile file = read_checkpoint_file(path);
    restore_checkpoint(file, identity, m, dynamics);
    const double rd = seconds_since(t0);
    write_min = std::min(write_min, w);
    write_max = std::max(write_max, w);
    read_min = std::min(read_min, rd);
    read_max = std::max(read_max, rd);
  }
  const auto bytes = static_cast<double>(std::filesystem::file_size(path));
  std::printf("%s: %zu points, %zu bonds (model built in %.1f s)\n", label, m.points.owned, m.bonds.bond_count(),
              build_seconds);
  std::printf(
      "  checkpoint %.1f MB (%.0f bytes per point); write %.2f-%.2f s (%.0f MB/s best), read + restore %.2f-%.2f s\n",
      bytes / 1e6, bytes / static_cast<double>(m.points.owned), write_min, write_max, bytes / write_min / 1e6, read_min,
      read_max);
  std::filesystem::remove(path);
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  const std::string directory =
      argc > 2 ? argv[2] : (std::filesystem::temp_directory_path() / "mppm-bench-checkpoint").string();
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 3;
  std::filesystem::create_directories(directory);
  const PointCloud cloud = cube(n, 5e-4);
  measure("3-D micropolar, elastic", cloud, false, directory, repeats);
  measure("3-D micropolar, damage", cloud, true, directory, repeats);
  return 0;
}
