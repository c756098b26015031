// Run-directory generator for postprocessor tests and benchmarks (see the header).
#include "test_post_run_fixture.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"

namespace mppm::post::testing {
namespace fs = std::filesystem;

namespace {

constexpr int kLayerRows = 2;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

std::int64_t fixture_points(const RunFixture& f) { return static_cast<std::int64_t>(f.nx) * (f.ny + 2 * kLayerRows); }

std::vector<std::string> write_run_directory(const std::string& directory, const RunFixture& f) {
  const fs::path dir(directory);
  fs::create_directories(dir / run_layout::snapshot_dir);
  const double dx = f.spacing;
  const double width = f.nx * dx, height = f.ny * dx;

  // Reference points: layer rows of the bottom (region 1) and top (region 2) boundaries.
  Snapshot reference;
  reference.dimension = 2;
  std::vector<double> position, volume, region, boundary_id;
  for (int j = -kLayerRows; j < f.ny + kLayerRows; ++j)
    for (int i = 0; i < f.nx; ++i) {
      position.insert(position.end(), {(i + 0.5) * dx, (j + 0.5) * dx, 0.0});
      volume.push_back(dx * dx * 0.01);
      const int r = j < 0 ? 1 : (j >= f.ny ? 2 : 0);
      region.push_back(r);
      boundary_id.push_back(r);
    }
  const std::size_t n = volume.size();
  reference.point_count = n;
  reference.fields = {
      {"position", 3, position}, {"volume", 1, volume}, {"region", 1, region}, {"boundary_id", 1, boundary_id}};
  write_snapshot(reference, (dir / run_layout::reference).string());

  std::vector<std::string> files;
  std::ostringstream listing;
  for (int k = 0; k < f.snapshots; ++k) {
    const double t = k * f.snapshot_interval;
    const double s = f.snapshots > 1 ? static_cast<double>(k) / (f.snapshots - 1) : 1.0;
    Snapshot snap;
    snap.dimension = 2;
    snap.step = 40 * k;
    snap.time = t;
    snap.point_count = n;
    std::vector<double> u(2 * n), v(2 * n), w(n), d(n), e(n), sigma(9 * n), eps(9 * n), m(3 * n), phi(n);
    const double tip = 0.5 * width * s;  // crack tip, growing from the left edge
    for (std::size_t i = 0; i < n; ++i) {
      const double x = position[3 * i], y = position[3 * i + 1];
      u[2 * i] = 1e-4 * x * s + 1e-7 * std::sin(1000.0 * y);
      u[2 * i + 1] = -2e-4 * y * s;
      v[2 * i] = 1e-4 * x / (f.snapshot_interval * (f.snapshots - 1) + 1e-30);
      v[2 * i + 1] = 0.3 * std::cos(500.0 * x);
      w[i] = 0.01 * std::sin(x / width * 3.14159) * s;
      const bool crack = std::fabs(y - 0.5 * height) < dx && x < 0.2 * width + tip;
      d[i] = region[i] != 0 ? 0.0 : (crack ? 0.5 : 0.05 * s * (x / width));
      const double along = (x - 0.5 * width) * 0.8 + (y - 0.5 * height) * 0.6;  // band across
      const double across = -(x - 0.5 * width) * 0.6 + (y - 0.5 * height) * 0.8;
      e[i] = 0.02 * s * std::exp(-across * across / (2.0 * 9.0 * dx * dx)) + 1e-6 * along;
      for (int c = 0; c < 9; ++c) {
        sigma[9 * i + c] = 1e6 * s * (1.0 + c) * (1.0 + x / width) + (c == 1 ? 2e5 : 0.0) - (c == 3 ? 1e5 : 0.0);
        eps[9 * i + c] = 1e-4 * s * (c + 1) * y / height;
      }
      m[3 * i] = 10.0 * s * x / width;
      m[3 * i + 1] = -5.0 * s * y / height;
      m[3 * i + 2] = 0.0;
      phi[i] = 0.05 + 0.01 * s * x / width;
    }
    snap.fields.push_back({"displacement", 2, u});
    if (f.micropolar) snap.fields.push_back({"rotation", 1, w});
    snap.fields.push_back({"velocity", 2, v});
    if (f.damage) snap.fields.push_back({"damage", 1, d});
    if (f.plasticity) snap.fields.push_back({"plastic_shear_strain", 1, e});
    if (f.stress) {
      if (f.stress_components == 4) {
        std::vector<double> plane_sigma(4 * n), plane_eps(4 * n);
        for (std::size_t i = 0; i < n; ++i)
          for (int c = 0; c < 4; ++c) {
            plane_sigma[4 * i + c] = sigma[9 * i + (c / 2) * 3 + c % 2];
            plane_eps[4 * i + c] = eps[9 * i + (c / 2) * 3 + c % 2];
          }
        snap.fields.push_back({"stress", 4, plane_sigma});
        snap.fields.push_back({"strain", 4, plane_eps});
      } else {
        snap.fields.push_back({"stress", 9, sigma});
        snap.fields.push_back({"strain", 9, eps});
      }
      snap.fields.push_back({"porosity", 1, phi});
    }
    if (f.micropolar) snap.fields.push_back({"couple_stress", 3, m});
    const std::string name = std::string(run_layout::snapshot_dir) + "/" + run_layout::snapshot_name(snap.step);
    write_snapshot(snap, (dir / name).string());
    files.push_back((dir / name).string());
    listing << (k ? ", " : "") << "{\"file\": \"" << name << "\", \"step\": " << snap.step
            << ", \"time_s\": " << number(t) << "}";
  }

  std::vector<std::string> effects;
  if (f.micropolar) effects.push_back("micropolar");
  if (f.plasticity) effects.push_back("viscoplasticity");
  if (f.damage) effects.push_back("damage");
  std::string effect_list;
  for (const auto& e : effects) effect_list += (effect_list.empty() ? "\"" : ", \"") + e + "\"";
  const double end_time = (f.snapshots - 1) * f.snapshot_interval;
  write_text(dir / run_layout::run_info,
             "{\"status\": \"" + f.status + "\", \"message\": \"" + f.message + "\", \"points\": " + std::to_string(n) +
                 ", \"bonds\": " + std::to_string(28 * n) + ", \"steps\": " + std::to_string(40 * (f.snapshots - 1)) +
                 ", \"time_s\": " + number(end_time) + ", \"wall_seconds\": 1.5, \"threads\": 2, \"effects\": [" +
                 effect_list +
                 "], \"dimension\": 2, \"time_step_s\": 2.5e-08, \"critical_time_step_s\": 3e-08, "
                 "\"limiting_mode\": \"translational\", \"snapshots\": [" +
                 listing.str() + "], \"detached_points\": 0}\n");

  std::string material =
      "material:\n  model: cosserat-elastic\n  density: 2650\n  solid_fraction: 0.95\n"
      "  lambda: 14000000000\n  mu: 14000000000\n";
  if (f.micropolar) material += "  mu_c: 4667000000\n  couple_moduli: [0, 0, 56000]\n  length_scale: 0.002\n";
  if (f.damage) material += "  damage:\n    critical_energy_release_rate: 160\n    no_fail_depth: 0.002\n";
  if (f.plasticity)
    material +=
        "  viscoplasticity:\n    model: drucker-prager-perzyna\n    friction_angle: 35 deg\n"
        "    dilatancy_angle: 15.000000000000002 deg\n    cohesion: 350000\n    hardening: -1000000\n"
        "    viscosity: 10000\n    residual_cohesion: 3500\n    cone_match: triaxial-compression\n";
  write_text(
      dir / run_layout::resolved_scene,
      "# Resolved scene (test fixture)\nmppm: 1\nname: fixture\ndimension: 2\nthickness: 0.001\n"
      "geometry:\n  file: /nonexistent/fixture.geo\n  unit: m\n  spacing: " +
          number(dx) + "\n  horizon_factor: " + number(f.horizon_factor) + "\n  precracks: []\n" + material +
          "effects: [" +
          [&] {
            std::string s;
            for (const auto& e : effects) s += (s.empty() ? "" : ", ") + e;
            return s;
          }() +
          "]\nboundary_conditions:\n"
          "  - name: bottom\n    boundary: bottom\n    type: velocity\n    value: [free, 0.05]\n"
          "  - name: top\n    boundary: top\n    type: velocity\n    value: [free, -0.05]\n"
          "time:\n  end: " +
          number(end_time) + "\n  step: 2.5e-08\n");

  // load.csv: rows every quarter snapshot interval; top/bottom move at 0.05 m/s towards each
  // other, the reaction rises then softens (peak at 60% of the run).
  std::ostringstream load;
  load << "time_s,bottom_ux_m,bottom_uy_m,bottom_Fx_N,bottom_Fy_N,top_ux_m,top_uy_m,top_Fx_N,top_Fy_N\n";
  const int rows = 4 * (f.snapshots - 1) + 1;
  for (int r = 0; r < rows; ++r) {
    const double t = r * 0.25 * f.snapshot_interval;
    const double phase = rows > 1 ? static_cast<double>(r) / (rows - 1) : 0.0;
    const double force = 1000.0 * (phase / 0.6) * std::exp(1.0 - phase / 0.6);  // peak 1 kN at 60%
    load << number(t) << ',' << 0.0 << ',' << number(0.05 * t) << ',' << number(0.01 * force) << ',' << number(force)
         << ',' << 0.0 << ',' << number(-0.05 * t) << ',' << number(-0.01 * force) << ',' << number(-force) << '\n';
  }
  write_text(dir / run_layout::load, load.str());
  write_text(dir / run_layout::energy,
             "time_s,kinetic_J,rotational_kinetic_J,elastic_J,stabilization_J,plastic_dissipation_J,"
             "fracture_dissipation_J,external_work_J,balance_error\n0,0,0,0,0,0,0,0,0\n");
  write_text(dir / run_layout::log, "test fixture\n");
  return files;
}

}  // namespace mppm::post::testing
