// mppm-bench-preprocess: preprocess a 3-D CAD part (geometry/notched_specimen_3d.step, read
// through OpenCASCADE) into about one million lattice points, with a kinematic layer and a
// loaded face, write POINTS.vtp, and report the time of every phase and the peak memory
// (getrusage). Not a test: run it by hand or from workflows.
//   mppm-bench-preprocess [--spacing MM] [--threads N] [--output FILE]
#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "preprocess/preprocessor.hpp"

int main(int argc, char** argv) {
  double spacing_mm = 0.27;  // (19777 mm^3 / 1e6)^(1/3): ~1.0e6 points
  std::string output = (std::filesystem::temp_directory_path() / "mppm_bench_points.vtp").string();
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--spacing"))
      spacing_mm = std::stod(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads"))
      omp_set_num_threads(std::stoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--output"))
      output = argv[i + 1];
  }
  const std::string scene_text =
      "mppm: 1\nname: bench-preprocess\ndimension: 3\n"
      "geometry:\n  file: notched_specimen_3d.step\n  unit: mm\n  spacing: " +
      std::to_string(spacing_mm) +
      " mm\n  horizon_factor: 3.015\n"
      "material: {density: 2650, lambda: 14 GPa, mu: 14 GPa}\neffects: []\n"
      "boundary_conditions:\n"
      "  - {box: [[-0.01 mm, -1 mm, -1 mm], [0.01 mm, 21 mm, 11 mm]], type: velocity, value: [0, 0, 0]}\n"
      "  - {box: [[99.99 mm, -1 mm, -1 mm], [100.01 mm, 21 mm, 11 mm]], type: traction, value: [1 MPa, 0, 0]}\n"
      "time: {end: 1 us, step: 0.025 us}\noutput: {interval: 0.25 us}\n";
  try {
    const auto start = std::chrono::steady_clock::now();
    const mppm::Scene scene =
        mppm::parse_scene(scene_text, std::string(MPPM_SOURCE_DIR) + "/geometry/bench_preprocess.yaml");
    mppm::pre::PreprocessOptions options;
    const mppm::pre::PreprocessResult result = mppm::pre::preprocess(scene, options);
    const auto written = std::chrono::steady_clock::now();
    mppm::write_point_cloud(result.cloud, output);
    const auto end = std::chrono::steady_clock::now();
    const mppm::PointCloud back = mppm::read_point_cloud(output);  // what the solver does first
    const auto read = std::chrono::steady_clock::now();
    if (back.size() != result.cloud.size()) throw std::runtime_error("read-back lost points");
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::cout << mppm::pre::format_report(scene, result, output);
    const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    std::printf(
        "benchmark: %zu points, %d threads: preprocess %.2f s, write %.2f s, total %.2f s "
        "(read back %.2f s), file %.1f MB, peak memory %.0f MiB (%.0f bytes/point)\n",
        result.cloud.size(), omp_get_max_threads(), seconds(start, written), seconds(written, end), seconds(start, end),
        seconds(end, read), static_cast<double>(std::filesystem::file_size(output)) / 1e6, usage.ru_maxrss / 1024.0,
        usage.ru_maxrss * 1024.0 / static_cast<double>(result.cloud.size()));
    std::filesystem::remove(output);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mppm-bench-preprocess: " << e.what() << "\n";
    return 2;
  }
}
