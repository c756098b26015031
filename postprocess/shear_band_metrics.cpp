// Shear bands: Hough transform of the points above half the peak strain finds up to two
// lines (conjugate bands), a weighted principal-axis fit refines each direction, and the
// strain profile across each band gives its full width at half maximum.
// Why Hough + PCA: a plain PCA of all band points cannot separate two crossing bands, and a
// Hough peak alone is quantized to its angle bin.
#include "postprocess/shear_band_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

namespace mppm::post {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr int kAngleBins = 720;  // 0.25 deg: finer than the refinement needs

struct Line {
  double cx = 0, cy = 0;     // a point on the line
  double direction = 0;      // [rad], in [0, pi)
  double sin_d = 0, cos_d = 1;  // of direction, cached: distances are evaluated per point
  Line() = default;
  Line(double x0, double y0, double d) : cx(x0), cy(y0), direction(d), sin_d(std::sin(d)), cos_d(std::cos(d)) {}
  double signed_distance(double px, double py) const { return -(px - cx) * sin_d + (py - cy) * cos_d; }
};

double angular_distance_deg(double a_deg, double b_deg) {
  double d = std::fabs(a_deg - b_deg);
  d = std::fmod(d, 180.0);
  return std::min(d, 180.0 - d);
}

// Weighted principal axis of the given points: the band's centre line.
Line principal_axis(const std::vector<double>& x, const std::vector<double>& y,
                    const std::vector<double>& w, const std::vector<std::size_t>& points,
                    const Line& fallback) {
  double sw = 0, sx = 0, sy = 0;
  for (std::size_t i : points) {
    sw += w[i];
    sx += w[i] * x[i];
    sy += w[i] * y[i];
  }
  if (!(sw > 0)) return fallback;
  const double mx = sx / sw, my = sy / sw;
  double cxx = 0, cxy = 0, cyy = 0;
  for (std::size_t i : points) {
    const double dx = x[i] - mx, dy = y[i] - my;
    cxx += w[i] * dx * dx;
    cxy += w[i] * dx * dy;
    cyy += w[i] * dy * dy;
  }
  // Direction of the largest eigenvector of the 2x2 covariance.
  double direction = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  if (direction < 0) direction += std::numbers::pi;
  if (direction >= std::numbers::pi) direction -= std::numbers::pi;
  return Line{mx, my, direction};
}

}  // namespace

ShearBandResult measure_shear_bands(const std::vector<double>& x, const std::vector<double>& y,
                                    const std::vector<double>& strain,
                                    const std::vector<char>& include,
                                    const ShearBandSettings& settings) {
  const std::size_t n = x.size();
  if (y.size() != n || strain.size() != n || include.size() != n)
    throw std::invalid_argument("measure_shear_bands: arrays of different lengths");
  if (!(settings.spacing > 0)) throw std::invalid_argument("measure_shear_bands: spacing <= 0");
  ShearBandResult result;

  std::vector<std::size_t> interior;
  double peak = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (include[i] && std::isfinite(strain[i])) {
      interior.push_back(i);
      peak = std::max(peak, strain[i]);
    }
  if (interior.empty()) {
    result.note = "no points away from the boundary layers";
    return result;
  }
  if (!(peak > 0.0)) {
    result.note = "no plastic shear strain in the interior";
    return result;
  }
  const double threshold = settings.threshold_fraction * peak;
  std::vector<std::size_t> band_points;
  for (std::size_t i : interior)
    if (strain[i] >= threshold) band_points.push_back(i);
  if (static_cast<double>(band_points.size()) >
      settings.max_band_area_fraction * static_cast<double>(interior.size())) {
    result.note = "plastic shear strain is not localized (more than half of the interior is "
                  "above half the peak)";
    return result;
  }

  // Bounding box and centre of the interior (the Hough offsets are measured from the centre).
  double xmin = std::numeric_limits<double>::max(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (std::size_t i : interior) {
    xmin = std::min(xmin, x[i]);
    xmax = std::max(xmax, x[i]);
    ymin = std::min(ymin, y[i]);
    ymax = std::max(ymax, y[i]);
  }
  const double cx = 0.5 * (xmin + xmax), cy = 0.5 * (ymin + ymax);
  const double radius = std::hypot(xmax - xmin, ymax - ymin) * 0.5 + settings.spacing;
  const auto offset_bins = static_cast<std::size_t>(std::ceil(2.0 * radius / settings.spacing)) + 1;
  std::vector<double> sin_table(kAngleBins), cos_table(kAngleBins);
  for (int a = 0; a < kAngleBins; ++a) {
    const double direction = a * (180.0 / kAngleBins) * kDegree;
    sin_table[a] = std::sin(direction);
    cos_table[a] = std::cos(direction);
  }
  // Strongest line through the given points (strain-weighted Hough transform over direction
  // and offset), skipping directions closer than `exclude_deg` to `excluded_direction_deg`.
  struct Peak {
    Line line;
    double weight = 0.0;
  };
  auto hough_peak = [&](const std::vector<std::size_t>& points, std::optional<double> excluded_direction_deg) {
    std::vector<double> accumulator(static_cast<std::size_t>(kAngleBins) * offset_bins, 0.0);
    for (std::size_t i : points) {
      const double px = x[i] - cx, py = y[i] - cy;
      for (int a = 0; a < kAngleBins; ++a) {
        const double rho = -px * sin_table[a] + py * cos_table[a];
        const auto bin = static_cast<std::size_t>(std::lround((rho + radius) / settings.spacing));
        accumulator[static_cast<std::size_t>(a) * offset_bins + bin] += strain[i];
      }
    }
    Peak found;
    std::size_t best = accumulator.size();
    for (std::size_t cell = 0; cell < accumulator.size(); ++cell) {
      const double direction_deg = static_cast<double>(cell / offset_bins) * (180.0 / kAngleBins);
      if (excluded_direction_deg &&
          angular_distance_deg(direction_deg, *excluded_direction_deg) < settings.min_separation_deg)
        continue;
      if (best == accumulator.size() || accumulator[cell] > accumulator[best]) best = cell;
    }
    if (best == accumulator.size()) return found;
    const double rho = static_cast<double>(best % offset_bins) * settings.spacing - radius;
    const double direction = static_cast<double>(best / offset_bins) * (180.0 / kAngleBins) * kDegree;
    // The point of the line nearest the centre.
    found.line = Line{cx - rho * std::sin(direction), cy + rho * std::cos(direction), direction};
    found.weight = accumulator[best];
    return found;
  };

  const double extent = std::min(xmax - xmin, ymax - ymin);
  const double window = std::max(settings.profile_window_fraction * extent, 3.0 * settings.spacing);
  const double bin_width = 0.25 * settings.spacing;
  const auto bins = static_cast<std::size_t>(std::ceil(2.0 * window / bin_width)) + 1;
  // Full width at half maximum of the mean strain in bins of signed distance across `lines[k]`
  // (interior points within the window that are nearer this line than the others), measured
  // above the profile's minimum.
  auto profile_width = [&](const std::vector<Line>& lines, std::size_t k) -> std::optional<double> {
    std::vector<double> sum(bins, 0.0);
    std::vector<std::size_t> count(bins, 0);
    for (std::size_t i : interior) {
      const double d = lines[k].signed_distance(x[i], y[i]);
      if (std::fabs(d) > window) continue;
      bool nearer_other = false;
      for (std::size_t o = 0; o < lines.size(); ++o)
        if (o != k && std::fabs(lines[o].signed_distance(x[i], y[i])) < std::fabs(d)) nearer_other = true;
      if (nearer_other) continue;
      const auto bin = static_cast<std::size_t>(std::lround((d + window) / bin_width));
      if (bin >= bins) continue;
      sum[bin] += strain[i];
      ++count[bin];
    }
    std::vector<double> position, mean;
    for (std::size_t b = 0; b < bins; ++b)
      if (count[b] > 0) {
        position.push_back(static_cast<double>(b) * bin_width - window);
        mean.push_back(sum[b] / static_cast<double>(count[b]));
      }
    if (mean.empty()) return std::nullopt;
    const auto top = static_cast<std::size_t>(std::max_element(mean.begin(), mean.end()) - mean.begin());
    const double baseline = *std::min_element(mean.begin(), mean.end());
    const double half = 0.5 * (mean[top] + baseline);
    std::optional<double> left, right;
    for (std::size_t b = top; b > 0; --b)
      if (mean[b - 1] < half) {
        const double t = (mean[b] - half) / (mean[b] - mean[b - 1]);
        left = position[b] + t * (position[b - 1] - position[b]);
        break;
      }
    for (std::size_t b = top; b + 1 < mean.size(); ++b)
      if (mean[b + 1] < half) {
        const double t = (mean[b] - half) / (mean[b] - mean[b + 1]);
        right = position[b] + t * (position[b + 1] - position[b]);
        break;
      }
    if (!left || !right || !(mean[top] > baseline)) return std::nullopt;
    return *right - *left;
  };

  // First band: the strongest line, refined by the principal axis of the band points close to
  // it (within 2 dx: the crossing of a conjugate band is small and symmetric there).
  const Peak first = hough_peak(band_points, std::nullopt);
  std::vector<Line> lines{first.line};
  {
    std::vector<std::size_t> core;
    for (std::size_t i : band_points)
      if (std::fabs(first.line.signed_distance(x[i], y[i])) <= 2.0 * settings.spacing) core.push_back(i);
    lines[0] = principal_axis(x, y, strain, core, first.line);
  }
  // Second (conjugate) band: the strongest line through the band points NOT explained by the
  // first band (farther than its half width + 2 dx), so that a short, wide single band never
  // passes for two.
  {
    const std::optional<double> first_width = profile_width(lines, 0);
    const double explained = 0.5 * first_width.value_or(0.0) + 2.0 * settings.spacing;
    std::vector<std::size_t> rest;
    for (std::size_t i : band_points)
      if (std::fabs(lines[0].signed_distance(x[i], y[i])) > explained) rest.push_back(i);
    if (!rest.empty()) {
      const Peak second = hough_peak(rest, lines[0].direction / kDegree);
      if (second.weight >= settings.second_band_ratio * first.weight) lines.push_back(second.line);
    }
  }

  // Refine: assign band points to the nearest line, fit each line's principal axis; twice,
  // so that the assignment follows the refined lines.
  std::vector<std::vector<std::size_t>> members(lines.size());
  for (int pass = 0; pass < 2; ++pass) {
    for (auto& m : members) m.clear();
    for (std::size_t i : band_points) {
      std::size_t best = 0;
      double best_distance = std::numeric_limits<double>::max();
      for (std::size_t k = 0; k < lines.size(); ++k) {
        const double d = std::fabs(lines[k].signed_distance(x[i], y[i]));
        if (d < best_distance) {
          best_distance = d;
          best = k;
        }
      }
      if (best_distance <= window) members[best].push_back(i);
    }
    for (std::size_t k = 0; k < lines.size(); ++k) lines[k] = principal_axis(x, y, strain, members[k], lines[k]);
  }

  // Final direction: a principal axis is biased when the interior cuts a band's ends
  // obliquely (by ~(w / L)^2: 4 degrees for a band only 4 widths long). Slices across the band
  // that the interior covers completely (out to one FWHM on both sides, no point given to the
  // other band) have unbiased strain centroids; a least-squares line through them is the band.
  for (std::size_t k = 0; k < lines.size(); ++k) {
    for (int pass = 0; pass < 10; ++pass) {  // converges geometrically; cheap
      const std::optional<double> width = profile_width(lines, k);
      if (!width) break;
      // Centroid window +-0.75 FWHM (symmetric about the current line, so the fixed point is
      // the band centre; wider windows leave too few complete slices in short interiors).
      const double half = 0.75 * *width;
      const double slice = 2.0 * settings.spacing;
      const double along_sin = std::sin(lines[k].direction), along_cos = std::cos(lines[k].direction);
      struct Slice {
        double weight = 0, weighted_d = 0, min_d = 0, max_d = 0;
        bool truncated = false, any = false;
      };
      std::map<long, Slice> slices;
      for (std::size_t i : interior) {
        const double d = lines[k].signed_distance(x[i], y[i]);
        if (std::fabs(d) > half) continue;
        const double along = (x[i] - lines[k].cx) * along_cos + (y[i] - lines[k].cy) * along_sin;
        Slice& sl = slices[std::lround(along / slice)];
        bool nearer_other = false;
        for (std::size_t o = 0; o < lines.size(); ++o)
          if (o != k && std::fabs(lines[o].signed_distance(x[i], y[i])) < std::fabs(d)) nearer_other = true;
        if (nearer_other) {
          sl.truncated = true;
          continue;
        }
        sl.min_d = sl.any ? std::min(sl.min_d, d) : d;
        sl.max_d = sl.any ? std::max(sl.max_d, d) : d;
        sl.any = true;
        sl.weight += strain[i];
        sl.weighted_d += strain[i] * d;
      }
      double s0 = 0, s1 = 0, s2 = 0, t0 = 0, t1 = 0;
      std::size_t used = 0;
      for (const auto& [index, sl] : slices) {
        if (sl.truncated || !sl.any || !(sl.weight > 0)) continue;
        if (sl.min_d > -half + settings.spacing || sl.max_d < half - settings.spacing) continue;
        const double along = static_cast<double>(index) * slice, centre = sl.weighted_d / sl.weight;
        s0 += 1;
        s1 += along;
        s2 += along * along;
        t0 += centre;
        t1 += along * centre;
        ++used;
      }
      const double determinant = s0 * s2 - s1 * s1;
      if (used < 3 || !(determinant > 0)) break;
      const double slope = (s0 * t1 - s1 * t0) / determinant;
      const double offset = (s2 * t0 - s1 * t1) / determinant;
      double direction = lines[k].direction + std::atan(slope);
      if (direction < 0) direction += std::numbers::pi;
      if (direction >= std::numbers::pi) direction -= std::numbers::pi;
      lines[k] = Line(lines[k].cx - offset * along_sin, lines[k].cy + offset * along_cos, direction);
    }
  }

  // Two lines that the refinement drew onto one direction are not conjugate bands (e.g. the
  // strain on both flanks of a void, which the Hough step took for two lines 30+ degrees apart):
  // keep the stronger one only.
  if (lines.size() == 2 &&
      angular_distance_deg(lines[0].direction / kDegree, lines[1].direction / kDegree) < settings.min_separation_deg) {
    result.note = "the second line converged to within " + std::to_string(static_cast<int>(settings.min_separation_deg)) +
                  " degrees of the first band's direction: one band";
    lines.pop_back();
    members.pop_back();
  }

  for (std::size_t k = 0; k < lines.size(); ++k) {
    ShearBand band;
    band.direction_deg = lines[k].direction / kDegree;
    band.angle_deg = band.direction_deg <= 90.0 ? band.direction_deg : 180.0 - band.direction_deg;
    band.centre_x = lines[k].cx;
    band.centre_y = lines[k].cy;
    band.points = members[k].size();
    band.width_m = profile_width(lines, k);
    result.bands.push_back(band);
  }

  double angle_sum = 0, width_sum = 0;
  std::size_t widths = 0;
  for (const auto& band : result.bands) {
    angle_sum += band.angle_deg;
    if (band.width_m) {
      width_sum += *band.width_m;
      ++widths;
    }
  }
  result.mean_angle_deg = angle_sum / static_cast<double>(result.bands.size());
  if (widths == result.bands.size()) result.mean_width_m = width_sum / static_cast<double>(widths);
  return result;
}

}  // namespace mppm::post
