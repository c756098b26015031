// load.csv parsing and reduction to load curves.
#include "postprocess/load_curve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/comma_list.hpp"
#include "common/input_error.hpp"

namespace mppm::post {
namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells = split_commas(line);
  for (std::string& cell : cells) cell = trim_blanks(cell);
  return cells;
}

const char kAxes[] = "xyz";

}  // namespace

LoadTable read_load_table(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": missing or unreadable (every run directory has load.csv)");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LoadTable table;
  if (text.empty()) throw InputError(path + ": empty (expected a header line starting with time_s)");
  const bool complete_last_line = text.back() == '\n';
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  table.columns = split_csv(line);
  if (table.columns.empty() || table.columns[0] != "time_s")
    throw InputError(path + ":1: header must start with time_s (found '" +
                     (table.columns.empty() ? std::string() : table.columns[0]) + "')");
  std::size_t number = 1;
  while (std::getline(lines, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    const bool last = lines.peek() == std::char_traits<char>::eof();
    const auto cells = split_csv(line);
    std::vector<double> row;
    bool ok = cells.size() == table.columns.size();
    for (std::size_t c = 0; ok && c < cells.size(); ++c) {
      char* end = nullptr;
      const double value = std::strtod(cells[c].c_str(), &end);
      if (cells[c].empty() || *end != '\0') ok = false;
      row.push_back(value);
    }
    if (!ok) {
      if (last && !complete_last_line) {
        table.notes.push_back(path + ": dropped an incomplete last line (the run was stopped while writing it)");
        break;
      }
      throw InputError(path + ":" + std::to_string(number) + ": expected " + std::to_string(table.columns.size()) +
                       " numbers separated by commas");
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

LoadCurve make_load_curve(const LoadTable& table) {
  LoadCurve curve;
  for (const auto& row : table.rows) curve.time.push_back(row[0]);
  auto boundary_index = [&](const std::string& name) {
    for (std::size_t b = 0; b < curve.boundaries.size(); ++b)
      if (curve.boundaries[b].name == name) return b;
    curve.boundaries.push_back(LoadedBoundary{name, {-1, -1, -1}, {-1, -1, -1}, 0});
    return curve.boundaries.size() - 1;
  };
  for (std::size_t c = 1; c < table.columns.size(); ++c) {
    const std::string& column = table.columns[c];
    // NAME_ux_m or NAME_Fx_N
    if (column.size() < 6) continue;
    const std::string suffix = column.substr(column.size() - 5);
    const char* axis = std::strchr(kAxes, suffix[2]);
    if (suffix[0] != '_' || axis == nullptr || *axis == '\0') continue;
    const int a = static_cast<int>(axis - kAxes);
    const std::string name = column.substr(0, column.size() - 5);
    if (suffix[1] == 'u' && suffix.substr(3) == "_m")
      curve.boundaries[boundary_index(name)].displacement_columns[a] = static_cast<int>(c);
    else if (suffix[1] == 'F' && suffix.substr(3) == "_N")
      curve.boundaries[boundary_index(name)].force_columns[a] = static_cast<int>(c);
  }
  auto peak = [&](int column) {
    double p = 0.0;
    if (column < 0) return -1.0;
    for (const auto& row : table.rows)
      if (std::isfinite(row[static_cast<std::size_t>(column)]))
        p = std::max(p, std::fabs(row[static_cast<std::size_t>(column)]));
    return p;
  };
  for (auto& b : curve.boundaries) {
    double best_force = -1, best_displacement = -1;
    for (int a = 0; a < 3; ++a) {
      const double f = peak(b.force_columns[a]), u = peak(b.displacement_columns[a]);
      if (f > best_force || (f == best_force && u > best_displacement)) {
        best_force = f;
        best_displacement = u;
        b.axis = a;
      }
    }
    std::vector<double> u, f;
    for (const auto& row : table.rows) {
      const int uc = b.displacement_columns[b.axis], fc = b.force_columns[b.axis];
      u.push_back(uc >= 0 ? row[static_cast<std::size_t>(uc)] : std::nan(""));
      f.push_back(fc >= 0 ? row[static_cast<std::size_t>(fc)] : std::nan(""));
    }
    curve.displacement.push_back(std::move(u));
    curve.force.push_back(std::move(f));
  }
  return curve;
}

PeakLoad find_peak_load(const LoadCurve& curve, const std::vector<std::string>& kinematic_boundaries) {
  PeakLoad result;
  if (curve.boundaries.empty()) return result;
  auto peak_of = [&](std::size_t b) {
    double p = 0.0;
    for (double f : curve.force[b])
      if (std::isfinite(f)) p = std::max(p, std::fabs(f));
    return p;
  };
  auto moves = [&](std::size_t b) {
    return std::any_of(curve.displacement[b].begin(), curve.displacement[b].end(),
                       [](double u) { return std::isfinite(u) && u != 0.0; });
  };
  std::optional<std::size_t> main;
  for (const auto& name : kinematic_boundaries)
    for (std::size_t b = 0; b < curve.boundaries.size() && !main; ++b)
      if (curve.boundaries[b].name == name && moves(b)) main = b;
  if (!main) {
    main = 0;
    for (std::size_t b = 1; b < curve.boundaries.size(); ++b)
      if (peak_of(b) > peak_of(*main)) main = b;
  }
  const std::size_t b = *main;
  result.boundary = curve.boundaries[b].name;
  result.axis = curve.boundaries[b].axis;
  std::optional<std::size_t> at;
  for (std::size_t r = 0; r < curve.time.size(); ++r)
    if (std::isfinite(curve.force[b][r]) && (!at || std::fabs(curve.force[b][r]) > std::fabs(curve.force[b][*at])))
      at = r;
  if (at) {
    result.peak_load_N = std::fabs(curve.force[b][*at]);
    if (std::isfinite(curve.displacement[b][*at]))
      result.displacement_at_peak_m = std::fabs(curve.displacement[b][*at]);
    result.time_at_peak_s = curve.time[*at];
  }
  return result;
}

std::string load_curve_csv(const LoadCurve& curve) {
  std::ostringstream out;
  out << "time_s";
  for (const auto& b : curve.boundaries)
    out << ',' << b.name << "_u" << kAxes[b.axis] << "_m," << b.name << "_F" << kAxes[b.axis] << "_N";
  out << '\n';
  char buffer[40];
  auto number = [&](double v) {
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
  };
  for (std::size_t r = 0; r < curve.time.size(); ++r) {
    out << number(curve.time[r]);
    for (std::size_t b = 0; b < curve.boundaries.size(); ++b) {
      out << ',' << number(curve.displacement[b][r]);
      out << ',' << number(curve.force[b][r]);
    }
    out << '\n';
  }
  return out.str();
}

}  // namespace mppm::post
