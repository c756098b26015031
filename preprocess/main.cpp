// mppm-preprocess: scene -> POINTS.vtp (material points, boundary layers, pre-cracks).
#include <omp.h>

#include <iostream>

#include "common/command_line.hpp"
#include "common/input_error.hpp"
#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "preprocess/preprocessor.hpp"
#include "solver/run_estimate.hpp"

namespace {

const char* kUsage =
    "Usage: mppm-preprocess SCENE.yaml -o POINTS.vtp [options]\n"
    "       mppm-preprocess SCENE.yaml --estimate [--threads N]\n"
    "Turns the scene's geometry (.geo .msh .step .stp .brep .stl, read with gmsh) into a\n"
    "uniform lattice of material points with boundary layers and pre-crack geometry.\n"
    "Options:\n"
    "  -o POINTS.vtp        output points file (VTK XML PolyData; written atomically)\n"
    "  --set key.path=value override a scene entry (repeatable), e.g. --set geometry.spacing=1mm\n"
    "  --threads N          threads for the inside test and the layers (gmsh meshes on one)\n"
    "  --verbose            show gmsh's own log\n"
    "  --estimate           no points file: print what mppm-solve will need for the scene (points,\n"
    "                       bonds, time step, steps, wall time at --threads N, peak memory)\n"
    "  --quiet              no report\n"
    "  --help, --version\n"
    "Exit codes: 0 success, 2 bad input (scene, geometry), 1 anything else.\n";

}  // namespace

int main(int argc, char** argv) {
  const mppm::CommandLineSpec spec{"mppm-preprocess", kUsage, {"-o"}, {"--verbose", "--estimate"}};
  return mppm::run_stage(argc, argv, spec, [&](const mppm::CommandLine& cl) {
    if (cl.positional.size() != 1) throw mppm::InputError("mppm-preprocess: expected one scene file (see --help)");
    const auto output = cl.option("-o");
    const bool estimate = cl.has_flag("--estimate");
    if (estimate && output) throw mppm::InputError("mppm-preprocess: --estimate writes no points file: no -o with it");
    if (!output && !estimate) throw mppm::InputError("mppm-preprocess: missing -o POINTS.vtp (see --help)");
    const mppm::Scene scene = mppm::load_scene(cl.positional[0], cl.overrides);
    for (const std::string& warning : scene.warnings)
      if (!cl.quiet) std::cerr << "mppm-preprocess: warning: " << warning << "\n";
    mppm::pre::PreprocessOptions options;
    options.verbose = cl.has_flag("--verbose");
    const mppm::pre::PreprocessResult result = mppm::pre::preprocess(scene, options);
    if (estimate) {
      // The bonds from the lattice (0: the families are the solver's): an upper bound near surfaces.
      std::cout << mppm::solver::format_run_estimate(
          scene, mppm::solver::estimate_run(scene, result.cloud, 0, omp_get_max_threads()));
      return 0;
    }
    mppm::write_point_cloud(result.cloud, *output);
    if (!cl.quiet) std::cout << mppm::pre::format_report(scene, result, *output);
    return 0;
  });
}
