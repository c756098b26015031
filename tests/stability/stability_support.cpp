// Implementation of the stability suite's shared machinery (see stability_support.hpp).
#include "tests/stability/stability_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "preprocess/preprocessor.hpp"
#include "solver/solve_run.hpp"

namespace mppm::stability {

namespace fs = std::filesystem;

bool long_form() {
  const char* form = std::getenv("MPPM_STABILITY_FORM");
  return form != nullptr && std::string(form) == "long";
}

const char* form_name() { return long_form() ? "long" : "short"; }

std::int64_t steps_for_form(std::int64_t short_steps, std::int64_t long_steps) {
  return long_form() ? long_steps : short_steps;
}

std::string scene_path(const std::string& name) {
  return (fs::path(MPPM_SOURCE_DIR) / "tests" / "stability" / "scenes" / name).string();
}

std::string work_path(const std::string& name) {
  return (fs::path(MPPM_BINARY_DIR) / "stability-work" / form_name() / name).string();
}

std::string fresh_directory(const std::string& name) {
  const fs::path dir = work_path(name);
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir.string();
}

std::string program(const std::string& name) { return (fs::path(MPPM_BINARY_DIR) / "bin" / name).string(); }

const PointCloud& points_of(const Scene& scene) {
  // The lattice depends only on geometry, spacing, horizon and boundary selections, which the
  // cases never override: one preprocessing per scene file.
  static std::map<std::string, std::unique_ptr<PointCloud>> cache;
  auto& slot = cache[scene.path + "|" + exact(scene.geometry.spacing) + "|" + exact(scene.geometry.horizon_factor)];
  if (!slot) slot = std::make_unique<PointCloud>(pre::preprocess(scene).cloud);
  return *slot;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string sci(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string exact(double value) { return sci(value, 17); }

namespace {

// The value text after "key": in a flat JSON object (run_info.json is written by our own
// writer: one level of keys, strings without escaped quotes in the fields read here).
std::string json_value(const std::string& json, const std::string& key) {
  // Built by appending: GCC 12 warns falsely (-Wrestrict, PR105329) on "\"" + std::string.
  std::string needle(1, '"');
  needle += key;
  needle += "\":";
  const auto at = json.find(needle);
  if (at == std::string::npos) return {};
  std::size_t p = at + needle.size();
  while (p < json.size() && json[p] == ' ') ++p;
  if (p < json.size() && json[p] == '"') {
    std::string out;
    for (++p; p < json.size() && json[p] != '"'; ++p) {
      if (json[p] == '\\' && p + 1 < json.size()) ++p;
      out += json[p];
    }
    return out;
  }
  const auto end = json.find_first_of(",}\n", p);
  return json.substr(p, end - p);
}

double json_number(const std::string& json, const std::string& key) {
  const std::string v = json_value(json, key);
  return v.empty() ? std::nan("") : std::strtod(v.c_str(), nullptr);
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, separator)) cells.push_back(cell);
  return cells;
}

std::string json_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

}  // namespace

RunReport read_run(const std::string& run_directory) {
  RunReport r;
  const std::string info = read_text(run_directory + "/" + run_layout::run_info);
  r.status = json_value(info, "status");
  r.message = json_value(info, "message");
  r.limiting_mode = json_value(info, "limiting_mode");
  r.steps = static_cast<std::int64_t>(json_number(info, "steps"));
  r.time_step = json_number(info, "time_step_s");
  r.critical_time_step = json_number(info, "critical_time_step_s");
  r.largest_time_step = json_number(info, "largest_time_step_s");

  r.detached_points = static_cast<std::int64_t>(json_number(info, "detached_points"));
  for (std::size_t at = info.find("{\"file\": \""); at != std::string::npos; at = info.find("{\"file\": \"", at + 1)) {
    const std::size_t begin = at + 10, end = info.find('"', begin);
    r.snapshots.push_back(run_directory + "/" + info.substr(begin, end - begin));
  }

  const std::string log = read_text(run_directory + "/" + run_layout::log);
  r.log = log;
  if (const auto at = log.find("driven by "); at != std::string::npos)
    r.driver = log.substr(at + 10, log.find('\n', at) - at - 10);
  if (const auto at = log.rfind("broken bonds "); at != std::string::npos)
    r.broken_bonds = std::strtoll(log.c_str() + at + 13, nullptr, 10);

  std::ifstream energy(run_directory + "/" + run_layout::energy);
  std::string line;
  std::getline(energy, line);
  const auto header = split(line, ',');
  auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw std::runtime_error(run_directory + "/energy.csv: no column " + name);
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t kinetic = column("kinetic_J"), rotational = column("rotational_kinetic_J"),
                    elastic = column("elastic_J"), stabilization = column("stabilization_J"),
                    work = column("external_work_J"), balance = column("balance_error"),
                    plastic = column("plastic_dissipation_J"), fracture = column("fracture_dissipation_J");
  double previous_plastic = 0.0, previous_fracture = 0.0;
  double initial_total = std::nan("");
  struct Row {
    double total, plastic, fracture, work;
  };
  std::vector<Row> rows;
  while (std::getline(energy, line)) {
    if (line.empty()) continue;
    const auto cells = split(line, ',');
    std::vector<double> v;
    for (const auto& c : cells) {
      v.push_back(std::strtod(c.c_str(), nullptr));
      if (!std::isfinite(v.back())) r.all_finite = false;
    }
    if (v.size() != header.size()) throw std::runtime_error(run_directory + "/energy.csv: ragged row");
    ++r.energy_rows;
    const double total = v[kinetic] + v[rotational] + v[elastic] + v[stabilization];
    r.worst_balance_error = std::max(r.worst_balance_error, std::abs(v[balance]));
    r.max_total_energy = std::max(r.max_total_energy, total);
    r.max_stabilization_energy = std::max(r.max_stabilization_energy, v[stabilization]);
    r.final_external_work = v[work];
    r.final_total_energy = total;
    // Dissipation is a sum of non-negative increments; 1e-12 relative allows the round-off of
    // the solver's summation, nothing more.
    if (v[plastic] < previous_plastic - 1e-12 * std::abs(previous_plastic))
      r.plastic_dissipation_never_decreases = false;
    previous_plastic = v[plastic];
    r.final_plastic_dissipation = v[plastic];
    if (v[fracture] < previous_fracture - 1e-12 * std::abs(previous_fracture))
      r.fracture_dissipation_never_decreases = false;
    if (r.energy_rows > 1) r.fracture_dissipation_decrease += std::max(0.0, previous_fracture - v[fracture]);
    previous_fracture = v[fracture];
    r.final_fracture_dissipation = v[fracture];
    if (std::isnan(initial_total)) initial_total = total;
    rows.push_back({total, v[plastic], v[fracture], v[work]});
  }
  // The solver's balance (explicit_dynamics.cpp), from the columns; the solver's scale also holds
  // the size of the kinetic terms, which energy.csv does not, hence the round-off rows skipped.
  auto scale_of = [&](const Row& w, double accounted) {
    return std::max(
        {std::abs(w.work), std::abs(accounted), w.total, initial_total, std::abs(w.plastic), std::abs(w.fracture)});
  };
  double largest = 0.0;
  for (const Row& w : rows) largest = std::max(largest, scale_of(w, w.total + w.plastic + w.fracture));
  for (const Row& w : rows) {
    const double with = w.total + w.plastic + w.fracture, without = w.total + w.plastic;
    if (scale_of(w, with) < 1e-12 * largest) continue;
    r.worst_recomputed_balance_error =
        std::max(r.worst_recomputed_balance_error, std::abs((with - initial_total - w.work) / scale_of(w, with)));
    r.worst_balance_without_fracture =
        std::max(r.worst_balance_without_fracture, std::abs((without - initial_total - w.work) / scale_of(w, without)));
  }
  return r;
}

RunReport solve_scene(const std::string& scene_file, const std::vector<std::string>& overrides,
                      const std::string& name) {
  const Scene scene = load_scene(scene_file, overrides);
  solver::SolveOptions options;
  options.run_directory = fresh_directory(name);
  options.points_file = scene_file + " (points made in memory)";
  solver::solve(scene, points_of(scene), options);
  return read_run(options.run_directory);
}

double auto_time_step(const std::string& scene_file, const std::vector<std::string>& overrides,
                      const std::string& name) {
  Scene scene = load_scene(scene_file, overrides);
  scene.time.end = 1e-12;  // one step (a whole number of steps of at most the auto step)
  solver::SolveOptions options;
  options.run_directory = fresh_directory(name + "-probe");
  solver::solve(scene, points_of(scene), options);
  // The bound the solver applies: the critical step, or the lower one of a damage run.
  return read_run(options.run_directory).largest_time_step * scene.time.safety;
}

CommandResult run_program(const std::string& executable, const std::vector<std::string>& arguments) {
  // Output to a file: std::system gives the exit status, the file gives the messages.
  static int counter = 0;
  const std::string capture_name = "command-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".txt";
  const fs::path capture = fs::path(MPPM_BINARY_DIR) / "stability-work" / capture_name;
  fs::create_directories(capture.parent_path());
  auto quote = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  std::string command = quote(executable);
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR105329) on " " + std::string.
  for (const auto& a : arguments) {
    command += ' ';
    command += quote(a);
  }
  command += " > ";
  command += quote(capture.string());
  command += " 2>&1";
  const int status = std::system(command.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.output = read_text(capture.string());
  fs::remove(capture);
  return r;
}

void record_margin(const MarginRecord& record) {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "stability" / form_name();
  fs::create_directories(dir);
  write_file_atomically((dir / (record.id + ".json")).string(), [&](std::ostream& out) {
    out << "{\"id\": \"" << json_escape(record.id) << "\", \"form\": \"" << form_name() << "\", \"hazard\": \""
        << json_escape(record.hazard) << "\", \"expected\": \"" << json_escape(record.expected)
        << "\", \"measured\": \"" << json_escape(record.measured) << "\", \"margin\": \"" << json_escape(record.margin)
        << "\", \"pass\": " << (record.pass ? "true" : "false") << "}\n";
  });
}

}  // namespace mppm::stability
