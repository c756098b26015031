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
#include <optional>
#include <stdexcept>
#include <string>

namespace mppm::post {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr int kAngleBins = 720;  // 0.25 deg: finer than the refinement needs

struct Line {
  double cx = 0, cy = 0;        // a point on the line
  double direction = 0;         // [rad], in [0, pi)
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
Line principal_axis(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& w,
                    const std::vector<std::size_t>& points, const Line& fallback) {
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

// The strain field of one measurement: the points it uses and the lengths its steps share.
struct StrainField {
  StrainField(const std::vector<double>& x_in, const std::vector<double>& y_in, const std::vector<double>& strain_in,
              const ShearBandSettings& settings_in)
      : x(x_in), y(y_in), strain(strain_in), settings(settings_in) {}
  const std::vector<double>& x;
  const std::vector<double>& y;
  const std::vector<double>& strain;
  const ShearBandSettings& settings;
  std::vector<std::size_t> interior;              // included points with a finite strain
  std::vector<std::size_t> band_points;           // interior points at or above the threshold
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;  // bounding box of the interior
  // Strain profiles across a band: half-window, bin width and bin count.
  double window = 0, bin_width = 0;
  std::size_t bins = 0;
};

// Fills field.interior and field.band_points; returns why there is no band to measure ("" if
// there is one).
std::string select_band_points(StrainField& field, const std::vector<char>& include) {
  const ShearBandSettings& settings = field.settings;
  double peak = 0.0;
  for (std::size_t i = 0; i < include.size(); ++i)
    if (include[i] && std::isfinite(field.strain[i])) {
      field.interior.push_back(i);
      peak = std::max(peak, field.strain[i]);
    }
  if (field.interior.empty()) return "no points away from the boundary layers";
  if (!(peak > 0.0)) return "no plastic shear strain in the interior";
  const double threshold = settings.threshold_fraction * peak;
  for (std::size_t i : field.interior)
    if (field.strain[i] >= threshold) field.band_points.push_back(i);
  if (static_cast<double>(field.band_points.size()) >
      settings.max_band_area_fraction * static_cast<double>(field.interior.size()))
    return "plastic shear strain is not localized (more than half of the interior is "
           "above half the peak)";
  return "";
}

// The bounding box of the interior, and the profile window and bins that follow from it.
void measure_extent(StrainField& field) {
  const ShearBandSettings& settings = field.settings;
  double xmin = std::numeric_limits<double>::max(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (std::size_t i : field.interior) {
    xmin = std::min(xmin, field.x[i]);
    xmax = std::max(xmax, field.x[i]);
    ymin = std::min(ymin, field.y[i]);
    ymax = std::max(ymax, field.y[i]);
  }
  field.xmin = xmin;
  field.xmax = xmax;
  field.ymin = ymin;
  field.ymax = ymax;
  const double extent = std::min(xmax - xmin, ymax - ymin);
  field.window = std::max(settings.profile_window_fraction * extent, 3.0 * settings.spacing);
  field.bin_width = 0.25 * settings.spacing;
  field.bins = static_cast<std::size_t>(std::ceil(2.0 * field.window / field.bin_width)) + 1;
}

struct Peak {
  Line line;
  double weight = 0.0;
};

// Strain-weighted Hough transform over direction and offset; offsets are measured from the
// centre of the interior's bounding box, in bins of dx.
class HoughTransform {
 public:
  explicit HoughTransform(const StrainField& field)
      : field_(field),
        cx_(0.5 * (field.xmin + field.xmax)),
        cy_(0.5 * (field.ymin + field.ymax)),
        radius_(std::hypot(field.xmax - field.xmin, field.ymax - field.ymin) * 0.5 + field.settings.spacing),
        offset_bins_(static_cast<std::size_t>(std::ceil(2.0 * radius_ / field.settings.spacing)) + 1),
        sin_table_(kAngleBins),
        cos_table_(kAngleBins) {
    for (int a = 0; a < kAngleBins; ++a) {
      const double direction = a * (180.0 / kAngleBins) * kDegree;
      sin_table_[a] = std::sin(direction);
      cos_table_[a] = std::cos(direction);
    }
  }

  // Strongest line through the given points, skipping directions closer than
  // min_separation_deg to `excluded_direction_deg`.
  Peak strongest_line(const std::vector<std::size_t>& points, std::optional<double> excluded_direction_deg) const {
    const ShearBandSettings& settings = field_.settings;
    std::vector<double> accumulator(static_cast<std::size_t>(kAngleBins) * offset_bins_, 0.0);
    for (std::size_t i : points) {
      const double px = field_.x[i] - cx_, py = field_.y[i] - cy_;
      for (int a = 0; a < kAngleBins; ++a) {
        const double rho = -px * sin_table_[a] + py * cos_table_[a];
        const auto bin = static_cast<std::size_t>(std::lround((rho + radius_) / settings.spacing));
        accumulator[static_cast<std::size_t>(a) * offset_bins_ + bin] += field_.strain[i];
      }
    }
    Peak found;
    std::size_t best = accumulator.size();
    for (std::size_t cell = 0; cell < accumulator.size(); ++cell) {
      const double direction_deg = static_cast<double>(cell / offset_bins_) * (180.0 / kAngleBins);
      if (excluded_direction_deg &&
          angular_distance_deg(direction_deg, *excluded_direction_deg) < settings.min_separation_deg)
        continue;
      if (best == accumulator.size() || accumulator[cell] > accumulator[best]) best = cell;
    }
    if (best == accumulator.size()) return found;
    const double rho = static_cast<double>(best % offset_bins_) * settings.spacing - radius_;
    const double direction = static_cast<double>(best / offset_bins_) * (180.0 / kAngleBins) * kDegree;
    // The point of the line nearest the centre.
    found.line = Line{cx_ - rho * std::sin(direction), cy_ + rho * std::cos(direction), direction};
    found.weight = accumulator[best];
    return found;
  }

 private:
  const StrainField& field_;
  double cx_, cy_, radius_;
  std::size_t offset_bins_;
  std::vector<double> sin_table_, cos_table_;
};

// Whether another of `lines` is nearer to (px, py) than `d`, its signed distance from lines[k].
bool nearer_other_line(const std::vector<Line>& lines, std::size_t k, double px, double py, double d) {
  for (std::size_t o = 0; o < lines.size(); ++o)
    if (o != k && std::fabs(lines[o].signed_distance(px, py)) < std::fabs(d)) return true;
  return false;
}

// The non-empty bins of a strain profile across a line: bin positions and mean strains.
struct Profile {
  std::vector<double> position, mean;
};

// Mean strain in bins of signed distance across `lines[k]`, of the interior points within the
// window that are nearer this line than the others.
Profile strain_profile(const StrainField& field, const std::vector<Line>& lines, std::size_t k) {
  std::vector<double> sum(field.bins, 0.0);
  std::vector<std::size_t> count(field.bins, 0);
  for (std::size_t i : field.interior) {
    const double d = lines[k].signed_distance(field.x[i], field.y[i]);
    if (std::fabs(d) > field.window) continue;
    if (nearer_other_line(lines, k, field.x[i], field.y[i], d)) continue;
    const auto bin = static_cast<std::size_t>(std::lround((d + field.window) / field.bin_width));
    if (bin >= field.bins) continue;
    sum[bin] += field.strain[i];
    ++count[bin];
  }
  Profile profile;
  for (std::size_t b = 0; b < field.bins; ++b)
    if (count[b] > 0) {
      profile.position.push_back(static_cast<double>(b) * field.bin_width - field.window);
      profile.mean.push_back(sum[b] / static_cast<double>(count[b]));
    }
  return profile;
}

// Full width at half maximum of a profile, measured above the profile's minimum.
std::optional<double> full_width_at_half_maximum(const Profile& profile) {
  const std::vector<double>& position = profile.position;
  const std::vector<double>& mean = profile.mean;
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
}

std::optional<double> profile_width(const StrainField& field, const std::vector<Line>& lines, std::size_t k) {
  return full_width_at_half_maximum(strain_profile(field, lines, k));
}

// The first band and, if there is one, its conjugate.
std::vector<Line> find_band_lines(const StrainField& field, const HoughTransform& hough) {
  const ShearBandSettings& settings = field.settings;
  const std::vector<double>& x = field.x;
  const std::vector<double>& y = field.y;
  // First band: the strongest line, refined by the principal axis of the band points close to
  // it (within 2 dx: the crossing of a conjugate band is small and symmetric there).
  const Peak first = hough.strongest_line(field.band_points, std::nullopt);
  std::vector<Line> lines{first.line};
  {
    std::vector<std::size_t> core;
    for (std::size_t i : field.band_points)
      if (std::fabs(first.line.signed_distance(x[i], y[i])) <= 2.0 * settings.spacing) core.push_back(i);
    lines[0] = principal_axis(x, y, field.strain, core, first.line);
  }
  // Second (conjugate) band: the strongest line through the band points NOT explained by the
  // first band (farther than its half width + 2 dx), so that a short, wide single band never
  // passes for two.
  const std::optional<double> first_width = profile_width(field, lines, 0);
  const double explained = 0.5 * first_width.value_or(0.0) + 2.0 * settings.spacing;
  std::vector<std::size_t> rest;
  for (std::size_t i : field.band_points)
    if (std::fabs(lines[0].signed_distance(x[i], y[i])) > explained) rest.push_back(i);
  if (!rest.empty()) {
    const Peak second = hough.strongest_line(rest, lines[0].direction / kDegree);
    if (second.weight >= settings.second_band_ratio * first.weight) lines.push_back(second.line);
  }
  return lines;
}

// Refine: assign band points to the nearest line, fit each line's principal axis; twice, so
// that the assignment follows the refined lines. Returns the band points of each line.
std::vector<std::vector<std::size_t>> fit_lines_to_their_points(const StrainField& field, std::vector<Line>& lines) {
  std::vector<std::vector<std::size_t>> members(lines.size());
  for (int pass = 0; pass < 2; ++pass) {
    for (auto& m : members) m.clear();
    for (std::size_t i : field.band_points) {
      std::size_t best = 0;
      double best_distance = std::numeric_limits<double>::max();
      for (std::size_t k = 0; k < lines.size(); ++k) {
        const double d = std::fabs(lines[k].signed_distance(field.x[i], field.y[i]));
        if (d < best_distance) {
          best_distance = d;
          best = k;
        }
      }
      if (best_distance <= field.window) members[best].push_back(i);
    }
    for (std::size_t k = 0; k < lines.size(); ++k)
      lines[k] = principal_axis(field.x, field.y, field.strain, members[k], lines[k]);
  }
  return members;
}

// A slice across a band: the strain-weighted distances of its points from the line, and
// whether another band took some of them.
struct Slice {
  double weight = 0, weighted_d = 0, min_d = 0, max_d = 0;
  bool truncated = false, any = false;
};

// Slices of `slice` length along lines[k] (index = along / slice) of the interior points
// within `half` of it.
std::map<long, Slice> slices_along(const StrainField& field, const std::vector<Line>& lines, std::size_t k, double half,
                                   double slice, double along_sin, double along_cos) {
  std::map<long, Slice> slices;
  for (std::size_t i : field.interior) {
    const double d = lines[k].signed_distance(field.x[i], field.y[i]);
    if (std::fabs(d) > half) continue;
    const double along = (field.x[i] - lines[k].cx) * along_cos + (field.y[i] - lines[k].cy) * along_sin;
    Slice& sl = slices[std::lround(along / slice)];
    if (nearer_other_line(lines, k, field.x[i], field.y[i], d)) {
      sl.truncated = true;
      continue;
    }
    sl.min_d = sl.any ? std::min(sl.min_d, d) : d;
    sl.max_d = sl.any ? std::max(sl.max_d, d) : d;
    sl.any = true;
    sl.weight += field.strain[i];
    sl.weighted_d += field.strain[i] * d;
  }
  return slices;
}

// One step towards the band centre: the least-squares line through the strain centroids of the
// complete slices (out to `half` - dx on both sides, none truncated); false if that line is
// undetermined (fewer than 3 slices).
bool fit_line_to_slice_centroids(const std::map<long, Slice>& slices, double half, double slice, double spacing,
                                 double along_sin, double along_cos, Line& line) {
  double s0 = 0, s1 = 0, s2 = 0, t0 = 0, t1 = 0;
  std::size_t used = 0;
  for (const auto& [index, sl] : slices) {
    if (sl.truncated || !sl.any || !(sl.weight > 0)) continue;
    if (sl.min_d > -half + spacing || sl.max_d < half - spacing) continue;
    const double along = static_cast<double>(index) * slice, centre = sl.weighted_d / sl.weight;
    s0 += 1;
    s1 += along;
    s2 += along * along;
    t0 += centre;
    t1 += along * centre;
    ++used;
  }
  const double determinant = s0 * s2 - s1 * s1;
  if (used < 3 || !(determinant > 0)) return false;
  const double slope = (s0 * t1 - s1 * t0) / determinant;
  const double offset = (s2 * t0 - s1 * t1) / determinant;
  double direction = line.direction + std::atan(slope);
  if (direction < 0) direction += std::numbers::pi;
  if (direction >= std::numbers::pi) direction -= std::numbers::pi;
  line = Line(line.cx - offset * along_sin, line.cy + offset * along_cos, direction);
  return true;
}

// Final direction: a principal axis is biased when the interior cuts a band's ends
// obliquely (by ~(w / L)^2: 4 degrees for a band only 4 widths long). Slices across the band
// that the interior covers completely (out to one FWHM on both sides, no point given to the
// other band) have unbiased strain centroids; a least-squares line through them is the band.
void straighten_along_slices(const StrainField& field, std::vector<Line>& lines, std::size_t k) {
  for (int pass = 0; pass < 10; ++pass) {  // converges geometrically; cheap
    const std::optional<double> width = profile_width(field, lines, k);
    if (!width) break;
    // Centroid window +-0.75 FWHM (symmetric about the current line, so the fixed point is
    // the band centre; wider windows leave too few complete slices in short interiors).
    const double half = 0.75 * *width;
    const double slice = 2.0 * field.settings.spacing;
    const double along_sin = std::sin(lines[k].direction), along_cos = std::cos(lines[k].direction);
    const std::map<long, Slice> slices = slices_along(field, lines, k, half, slice, along_sin, along_cos);
    if (!fit_line_to_slice_centroids(slices, half, slice, field.settings.spacing, along_sin, along_cos, lines[k]))
      break;
  }
}

// The bands of the refined lines, and their mean angle and (if every band has one) mean width.
void describe_bands(const StrainField& field, const std::vector<Line>& lines,
                    const std::vector<std::vector<std::size_t>>& members, ShearBandResult& result) {
  for (std::size_t k = 0; k < lines.size(); ++k) {
    ShearBand band;
    band.direction_deg = lines[k].direction / kDegree;
    band.angle_deg = band.direction_deg <= 90.0 ? band.direction_deg : 180.0 - band.direction_deg;
    band.centre_x = lines[k].cx;
    band.centre_y = lines[k].cy;
    band.points = members[k].size();
    band.width_m = profile_width(field, lines, k);
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
}

}  // namespace

ShearBandResult measure_shear_bands(const std::vector<double>& x, const std::vector<double>& y,
                                    const std::vector<double>& strain, const std::vector<char>& include,
                                    const ShearBandSettings& settings) {
  const std::size_t n = x.size();
  if (y.size() != n || strain.size() != n || include.size() != n)
    throw std::invalid_argument("measure_shear_bands: arrays of different lengths");
  if (!(settings.spacing > 0)) throw std::invalid_argument("measure_shear_bands: spacing <= 0");
  ShearBandResult result;
  StrainField field(x, y, strain, settings);
  result.note = select_band_points(field, include);
  if (!result.note.empty()) return result;
  measure_extent(field);

  const HoughTransform hough(field);
  std::vector<Line> lines = find_band_lines(field, hough);
  std::vector<std::vector<std::size_t>> members = fit_lines_to_their_points(field, lines);
  for (std::size_t k = 0; k < lines.size(); ++k) straighten_along_slices(field, lines, k);

  // Two lines that the refinement drew onto one direction are not conjugate bands (e.g. the
  // strain on both flanks of a void, which the Hough step took for two lines 30+ degrees apart):
  // keep the stronger one only.
  if (lines.size() == 2 &&
      angular_distance_deg(lines[0].direction / kDegree, lines[1].direction / kDegree) < settings.min_separation_deg) {
    result.note = "the second line converged to within " +
                  std::to_string(static_cast<int>(settings.min_separation_deg)) +
                  " degrees of the first band's direction: one band";
    lines.pop_back();
    members.pop_back();
  }
  describe_bands(field, lines, members, result);
  return result;
}

}  // namespace mppm::post
