// 3-D crack metrics from the crack_area field (crack_area_metrics.hpp for the definitions).
#include "postprocess/crack_area_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "postprocess/point_grid.hpp"

namespace mppm::post {

class CrackAreaTracker::Grid {
 public:
  Grid(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
       const std::vector<std::size_t>& members, double cell)
      : grid(x, y, z, members, cell) {}
  PointGrid grid;
};

CrackAreaTracker::CrackAreaTracker(std::vector<double> x, std::vector<double> y, std::vector<double> z,
                                   std::vector<char> include, double spacing)
    : x_(std::move(x)), y_(std::move(y)), z_(std::move(z)), include_(std::move(include)), spacing_(spacing) {
  if (!(spacing_ > 0.0)) throw std::invalid_argument("CrackAreaTracker: the spacing must be positive");
  in_reference_.assign(x_.size(), 0);
  distance_.assign(x_.size(), std::numeric_limits<double>::quiet_NaN());
}

CrackAreaTracker::~CrackAreaTracker() = default;

void CrackAreaTracker::set_reference(const std::vector<std::size_t>& crack_points, double time) {
  reference_ = crack_points;
  for (std::size_t i : reference_) in_reference_[i] = 1;
  grid_ = std::make_unique<Grid>(x_, y_, z_, reference_, 2.0 * spacing_);
  if (!metrics_.frames.empty()) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "no pre-crack in the first snapshot: the front advance is measured from the crack points of "
                  "t = %.6g s, where the crack appeared",
                  time);
    metrics_.notes.emplace_back(text);
  }
}

// The nearest reference point: search radii growing by doubling until one holds a reference point;
// the nearest of those is the nearest of all (every point within the radius is visited).
double CrackAreaTracker::distance_to_reference(std::size_t i) const {
  for (double radius = 2.0 * spacing_;; radius *= 2.0) {
    double best2 = std::numeric_limits<double>::infinity();
    grid_->grid.for_each_within(x_[i], y_[i], z_[i], radius, [&](std::size_t q) {
      const double dx = x_[q] - x_[i], dy = y_[q] - y_[i], dz = z_[q] - z_[i];
      best2 = std::min(best2, dx * dx + dy * dy + dz * dz);
    });
    if (best2 <= radius * radius) return std::sqrt(best2);
  }
}

void CrackAreaTracker::add_frame(double time, const std::vector<double>& crack_area) {
  if (crack_area.size() != x_.size())
    throw std::invalid_argument("CrackAreaTracker: a crack_area field of " + std::to_string(crack_area.size()) +
                                " points, the run has " + std::to_string(x_.size()));
  CrackAreaFrame frame;
  frame.time = time;
  std::vector<std::size_t> crack_points;
  for (std::size_t i = 0; i < crack_area.size(); ++i) {
    if (!include_[i]) continue;
    frame.total_area += crack_area[i];
    if (crack_area[i] >= front_point_area()) crack_points.push_back(i);
  }
  frame.crack_points = crack_points.size();
  if (metrics_.frames.empty()) metrics_.precrack_area_m2 = frame.total_area;
  frame.new_area = frame.total_area - metrics_.precrack_area_m2;
  if (!metrics_.start_time_s && frame.new_area >= start_area()) metrics_.start_time_s = time;
  if (!grid_ && !crack_points.empty()) set_reference(crack_points, time);
  if (grid_) {
    double advance = 0.0;
    for (std::size_t i : crack_points) {
      if (in_reference_[i]) continue;
      if (std::isnan(distance_[i])) distance_[i] = distance_to_reference(i);
      advance = std::max(advance, distance_[i]);
    }
    frame.front_advance = advance;
    if (!metrics_.front_advance_m || advance > *metrics_.front_advance_m) {
      metrics_.front_advance_m = advance;
      metrics_.front_advance_time_s = time;
    }
  }
  metrics_.area_m2 = frame.new_area;
  metrics_.frames.push_back(frame);
}

CrackAreaMetrics CrackAreaTracker::finish() const { return metrics_; }

CrackAreaMetrics measure_crack_area(const std::vector<double>& x, const std::vector<double>& y,
                                    const std::vector<double>& z, const std::vector<char>& include,
                                    const std::vector<double>& times, const std::vector<std::vector<double>>& areas,
                                    double spacing) {
  CrackAreaTracker tracker(x, y, z, include, spacing);
  for (std::size_t k = 0; k < times.size(); ++k) tracker.add_frame(times[k], areas[k]);
  return tracker.finish();
}

std::string crack_area_csv(const CrackAreaMetrics& metrics) {
  std::string text = "time_s,crack_area_m2,total_crack_area_m2,crack_front_advance_m\n";
  char row[128];
  for (const CrackAreaFrame& f : metrics.frames) {
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,", f.time, f.new_area, f.total_area);
    text += row;
    if (f.front_advance) {
      std::snprintf(row, sizeof row, "%.17g", *f.front_advance);
      text += row;
    }
    text += '\n';
  }
  return text;
}

}  // namespace mppm::post
