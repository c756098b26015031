// mppm-bench-postprocess: time and peak memory of postprocessing a million-point snapshot
// series (generated first, in the run-directory format of common/). Not a test: prints figures
// for postprocess/README.md.
// Usage: mppm-bench-postprocess [--points N] [--snapshots K] [--all-fields] [--keep] [--dir DIR]
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include "postprocess/postprocess_run.hpp"
#include "test_post_run_fixture.hpp"

namespace {

double peak_resident_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: KiB
}

double directory_mib(const std::filesystem::path& dir) {
  double bytes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) bytes += static_cast<double>(entry.file_size());
  return bytes / (1024.0 * 1024.0);
}

}  // namespace

int main(int argc, char** argv) {
  long points = 1000000;
  int snapshots = 5;
  bool all_fields = false, keep = false;
  std::string dir = (std::filesystem::temp_directory_path() / "mppm_bench_postprocess").string();
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--points" && a + 1 < argc)
      points = std::stol(argv[++a]);
    else if (arg == "--snapshots" && a + 1 < argc)
      snapshots = std::stoi(argv[++a]);
    else if (arg == "--all-fields")
      all_fields = true;
    else if (arg == "--keep")
      keep = true;
    else if (arg == "--dir" && a + 1 < argc)
      dir = argv[++a];
    else {
      std::cerr << "usage: mppm-bench-postprocess [--points N] [--snapshots K] [--all-fields] [--keep] [--dir DIR]\n";
      return 2;
    }
  }
  // A square-ish 2-D lattice of about `points` points (2 layer rows above and below).
  mppm::post::testing::RunFixture fixture;
  fixture.nx = static_cast<int>(std::lround(std::sqrt(static_cast<double>(points))));
  fixture.ny = static_cast<int>(points / fixture.nx) - 4;
  fixture.spacing = 1e-4;
  fixture.snapshots = snapshots;
  fixture.stress = all_fields;  // stress, strain (9 components each) and porosity
  std::filesystem::remove_all(dir);
  const auto t0 = std::chrono::steady_clock::now();
  mppm::post::testing::write_run_directory(dir + "/run", fixture);
  const auto t1 = std::chrono::steady_clock::now();
  const double generate_mib = peak_resident_mib();

  mppm::post::PostprocessOptions options;
  options.run_directory = dir + "/run";
  options.output_directory = dir + "/post";
  options.quiet = true;
  const auto result = mppm::post::postprocess_run(options);
  const auto t2 = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(t2 - t1).count();

  std::printf("mppm-bench-postprocess: %lld points, %d snapshots, fields: %s\n",
              static_cast<long long>(mppm::post::testing::fixture_points(fixture)), snapshots,
              all_fields ? "all (incl. stress, strain)"
                         : "displacement, rotation, velocity, damage, plastic_shear_strain, couple_stress");
  std::printf("  generate run directory: %.2f s (%.0f MiB on disk)\n", std::chrono::duration<double>(t1 - t0).count(),
              directory_mib(dir + "/run"));
  std::printf("  postprocess:            %.2f s total, %.2f s per snapshot (%zu frames, %.0f MiB written)\n", seconds,
              seconds / static_cast<double>(result.frames), result.frames, directory_mib(dir + "/post"));
  std::printf("  peak resident memory:   %.0f MiB (after generation: %.0f MiB)\n", peak_resident_mib(), generate_mib);
  if (!keep) std::filesystem::remove_all(dir);
  return 0;
}
