// Reading crack_path.csv and making the crack tracker's frames of it (crack_path_table.hpp).
#include "postprocess/crack_path_table.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "common/comma_list.hpp"
#include "common/crack_path.hpp"
#include "common/input_error.hpp"
#include "common/snapshot_file.hpp"

namespace mppm::post {

namespace {

std::string header_text() {
  std::string header;
  for (const std::string& c : run_files::crack_path_columns()) header += (header.empty() ? "" : ",") + c;
  return header;
}

// One row: the point (a whole number below point_count) and the time (finite); the position is
// not read (the reference points give it).
CrackArrival parse_row(const std::string& line, std::size_t point_count, const std::string& where) {
  const std::vector<std::string> cells = split_commas(line);
  if (cells.size() != run_files::crack_path_columns().size())
    throw InputError(where + ": expected " + std::to_string(run_files::crack_path_columns().size()) +
                     " values separated by commas (" + header_text() + ")");
  char* end = nullptr;
  const unsigned long long point = std::strtoull(cells[0].c_str(), &end, 10);
  if (cells[0].empty() || *end != '\0' || cells[0][0] == '-')
    throw InputError(where + ": point '" + cells[0] + "' is not a point index");
  if (point >= point_count)
    throw InputError(where + ": point " + cells[0] + " is not among the run's " + std::to_string(point_count) +
                     " points");
  const double time = std::strtod(cells.back().c_str(), &end);
  if (cells.back().empty() || *end != '\0' || !std::isfinite(time))
    throw InputError(where + ": time_s '" + cells.back() + "' is not a number");
  return {static_cast<std::size_t>(point), time};
}

}  // namespace

std::optional<std::vector<CrackArrival>> read_crack_path_table(const std::string& run_directory,
                                                               std::size_t point_count) {
  const std::string path = (std::filesystem::path(run_directory) / run_layout::crack_path).string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot be read");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.empty() || text.back() != '\n')
    throw InputError(path + ": incomplete (expected the header " + header_text() + " and whole lines)");
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  if (line != header_text()) throw InputError(path + ":1: expected the header " + header_text());
  std::vector<CrackArrival> arrivals;
  std::vector<char> listed(point_count, 0);
  for (std::size_t number = 2; std::getline(lines, line); ++number) {
    const std::string where = path + ":" + std::to_string(number);
    const CrackArrival a = parse_row(line, point_count, where);
    if (listed[a.point]) throw InputError(where + ": point " + std::to_string(a.point) + " is listed twice");
    if (!arrivals.empty() && a.time < arrivals.back().time)
      throw InputError(where + ": time_s earlier than the row before (rows are in arrival order)");
    listed[a.point] = 1;
    arrivals.push_back(a);
  }
  return arrivals;
}

std::vector<double> crack_frame_times(const std::vector<CrackArrival>& arrivals, double first, double last, double bin,
                                      double hold) {
  std::vector<double> changes{first};
  auto bin_of = [&](double t) { return bin > 0.0 ? std::ceil((t - first) / bin) : 0.0; };
  for (std::size_t k = 0; k < arrivals.size(); ++k) {
    const double t = arrivals[k].time;
    if (!(t > first) || t > last) continue;
    if (k + 1 < arrivals.size() && arrivals[k + 1].time == t) continue;  // the last row of this time
    // With bins, a change replaces the frame of an earlier change in its bin.
    if (bin > 0.0 && changes.size() > 1 && bin_of(changes.back()) == bin_of(t))
      changes.back() = t;
    else
      changes.push_back(t);
  }
  if (last > changes.back()) changes.push_back(last);
  std::vector<double> times{first};
  for (std::size_t k = 1; k < changes.size(); ++k) {
    if (hold > 0.0 && changes[k] - hold > times.back()) times.push_back(changes[k] - hold);
    times.push_back(changes[k]);
  }
  return times;
}

void add_table_frames(CrackTracker& tracker, const std::vector<CrackArrival>& arrivals,
                      const std::vector<double>& times) {
  std::vector<std::size_t> cracked;
  std::size_t next = 0;
  for (const double t : times) {
    while (next < arrivals.size() && arrivals[next].time <= t) cracked.push_back(arrivals[next++].point);
    tracker.add_cracked_frame(t, cracked);
  }
}

CrackFrameSource add_crack_path_frames(CrackTracker& tracker, const std::vector<CrackArrival>& arrivals, double first,
                                       double last, double time_step) {
  CrackFrameSource source{"crack_path table", time_step, 0};
  std::vector<double> times = crack_frame_times(arrivals, first, last, 0.0, time_step);
  if (times.size() > kMaxCrackTableFrames) {
    // Half as many bins as frames: each change may bring a frame of the path before it.
    source.resolution_s = (last - first) / static_cast<double>(kMaxCrackTableFrames / 2);
    times = crack_frame_times(arrivals, first, last, source.resolution_s, time_step);
  }
  add_table_frames(tracker, arrivals, times);
  source.frames = times.size();
  return source;
}

}  // namespace mppm::post
