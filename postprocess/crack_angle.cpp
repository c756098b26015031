// Crack angles at the pre-crack tips (crack_angle.hpp; the choices are explained in
// postprocess/README.md "Crack angle"). All lengths in metres, 2-D positions (x, y).
#include "postprocess/crack_angle.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <numbers>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "common/comma_list.hpp"
#include "common/input_error.hpp"
#include "common/units.hpp"
#include "postprocess/point_grid.hpp"

namespace mppm::post {
namespace {

// Links of the crack path, as the crack tracker's (crack_metrics.cpp): up to 2.3 dx, so that an
// inclined crack band, whose points are staggered on the lattice, stays one connected set.
constexpr double kLinkRadiusInSpacings = 2.3;
// A connected part of the ring is a crack if it is at least this long along its fitted line.
constexpr double kMinimumCrackExtentInSpacings = 3.0;
// A pre-crack part shorter than this along its axis has no reliable direction: its damage is
// a blob one horizon around its points.
constexpr double kMinimumPrecrackExtentInHorizons = 2.0;
// The crack points within this distance of a tip attach their connected part to the tip.
constexpr double kAttachRadiusInHorizons = 2.0;
// Default ring around the tip, in horizons (the README says why).
constexpr double kDefaultRangeFromInHorizons = 2.0;
constexpr double kDefaultRangeToInHorizons = 12.0;
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

using Vector2 = Eigen::Vector2d;

Vector2 position_of(const CrackAngleLattice& l, std::size_t i) { return {l.x[i], l.y[i]}; }
Vector2 planar(const Vector3& v) { return {v[0], v[1]}; }

std::string millimetres(double metres) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", metres * 1e3);
  return buffer;
}

std::string point_in_mm(const Vector2& p) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "(%.4g, %.4g) mm", p.x() * 1e3, p.y() * 1e3);
  return buffer;
}

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// The body points at or above the damage threshold, in index order.
std::vector<std::size_t> crack_points(const std::vector<char>& include, const std::vector<double>& damage,
                                      double threshold) {
  std::vector<std::size_t> points;
  for (std::size_t i = 0; i < include.size(); ++i)
    if (include[i] && damage[i] >= threshold) points.push_back(i);
  return points;
}

// The connected parts of `members` (links up to `link`): point indices in increasing order,
// the parts in the order of their first point.
std::vector<std::vector<std::size_t>> connected_parts(const CrackAngleLattice& l,
                                                      const std::vector<std::size_t>& members, double link) {
  std::vector<std::size_t> parent(members.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  std::vector<std::size_t> local(l.x.size(), kNone);
  for (std::size_t k = 0; k < members.size(); ++k) local[members[k]] = k;
  PointGrid grid(l.x, l.y, l.z, members, link);
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::size_t i = members[k];
    grid.for_each_within(l.x[i], l.y[i], l.z[i], link, [&](std::size_t j) {
      const std::size_t a = find_root(parent, k), b = find_root(parent, local[j]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    });
  }
  std::vector<std::size_t> part_of_root(members.size(), kNone);
  std::vector<std::vector<std::size_t>> parts;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::size_t root = find_root(parent, k);
    if (part_of_root[root] == kNone) {
      part_of_root[root] = parts.size();
      parts.emplace_back();
    }
    parts[part_of_root[root]].push_back(members[k]);
  }
  return parts;
}

// A straight line through points by total least squares: the principal axis of their
// covariance, through their centroid; s_min, s_max: the extreme projections on the axis.
struct LineFit {
  Vector2 centroid = Vector2::Zero();
  Vector2 axis = Vector2::UnitX();
  double s_min = 0, s_max = 0;
};

LineFit fit_line(const CrackAngleLattice& l, const std::vector<std::size_t>& points) {
  LineFit fit;
  for (std::size_t i : points) fit.centroid += position_of(l, i);
  fit.centroid /= static_cast<double>(points.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (std::size_t i : points) {
    const Vector2 r = position_of(l, i) - fit.centroid;
    covariance += r * r.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance);
  fit.axis = eigen.eigenvectors().col(1).normalized();  // eigenvalues increase
  fit.s_min = std::numeric_limits<double>::infinity();
  fit.s_max = -fit.s_min;
  for (std::size_t i : points) {
    const double s = (position_of(l, i) - fit.centroid).dot(fit.axis);
    fit.s_min = std::min(fit.s_min, s);
    fit.s_max = std::max(fit.s_max, s);
  }
  return fit;
}

// The tips of one connected part of the pre-crack: the ends of its principal axis whose points
// (those within dx of the end) are all farther than 2 dx from the free surface. An edge notch
// has one, an interior crack two, a crack through the body none.
std::vector<CrackTipSpec> tips_of_precrack_part(const CrackAngleLattice& l, const std::vector<std::size_t>& part,
                                                const CrackAngleSettings& settings, std::vector<std::string>& notes) {
  const LineFit fit = fit_line(l, part);
  if (fit.s_max - fit.s_min < kMinimumPrecrackExtentInHorizons * settings.horizon) {
    notes.push_back("a pre-crack part of " + std::to_string(part.size()) + " points around " +
                    point_in_mm(fit.centroid) + " is shorter than 2 horizons: it has no direction and no tip");
    return {};
  }
  std::vector<CrackTipSpec> tips;
  for (const double sign : {1.0, -1.0}) {
    const double end = sign > 0 ? fit.s_max : fit.s_min;
    bool at_surface = false;
    for (std::size_t i : part)
      if (sign * ((position_of(l, i) - fit.centroid).dot(fit.axis) - end) >= -settings.spacing && l.near_boundary[i])
        at_surface = true;
    if (at_surface) continue;
    const Vector2 tip = fit.centroid + end * fit.axis, direction = sign * fit.axis;
    tips.push_back({{tip.x(), tip.y(), l.z[part.front()]}, {direction.x(), direction.y(), 0.0}});
  }
  return tips;
}

// Tips of the whole pre-crack, ordered by y, then x.
std::vector<CrackTipSpec> tips_of_precrack(const CrackAngleLattice& l, const std::vector<std::size_t>& precrack,
                                           const CrackAngleSettings& settings, std::vector<std::string>& notes) {
  std::vector<CrackTipSpec> tips;
  for (const auto& part : connected_parts(l, precrack, kLinkRadiusInSpacings * settings.spacing)) {
    const auto more = tips_of_precrack_part(l, part, settings, notes);
    tips.insert(tips.end(), more.begin(), more.end());
  }
  std::sort(tips.begin(), tips.end(), [](const CrackTipSpec& a, const CrackTipSpec& b) {
    return a.position[1] != b.position[1] ? a.position[1] < b.position[1] : a.position[0] < b.position[0];
  });
  return tips;
}

// Half the width of a notch cut out of the body behind the tip: the smallest distance from the
// pre-crack line of the body points between one horizon and `far` behind the tip. About dx/2
// or less when the lattice runs through the notch (a notch made of cut bonds).
double notch_half_gap(const CrackAngleLattice& l, const Vector2& tip, const Vector2& direction, double near,
                      double far) {
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < l.x.size(); ++i) {
    if (!l.include[i]) continue;
    const Vector2 r = position_of(l, i) - tip;
    const double behind = -r.dot(direction);
    if (behind >= near && behind <= far) gap = std::min(gap, std::fabs(direction.x() * r.y() - direction.y() * r.x()));
  }
  return std::isfinite(gap) ? gap : 0.0;
}

// The geometry of the ring around one tip.
struct TipRing {
  Vector2 tip, direction;
  double from = 0, to = 0;
  double flank_width = 0;  // points behind the tip nearer the pre-crack line than this are flank damage
};

// The tips (indices) that a connected part of the crack reaches within `attach`.
std::vector<std::size_t> tips_reached(const CrackAngleLattice& l, const std::vector<std::size_t>& part,
                                      const std::vector<Vector2>& tips, double attach) {
  std::vector<std::size_t> reached;
  for (std::size_t o = 0; o < tips.size(); ++o)
    if (std::any_of(part.begin(), part.end(),
                    [&](std::size_t i) { return (position_of(l, i) - tips[o]).norm() <= attach; }))
      reached.push_back(o);
  return reached;
}

// Damage spreading along the notch faces, not a crack leaving the tip: behind the tip and within
// the flank width of the pre-crack line.
bool on_flank(const TipRing& ring, const Vector2& p) {
  const Vector2 r = p - ring.tip;
  const double across = std::fabs(ring.direction.x() * r.y() - ring.direction.y() * r.x());
  return r.dot(ring.direction) < 0 && across <= ring.flank_width;
}

// The ring points of the tip `t`: new crack points (not pre-crack) of the connected parts that
// reach within the attach radius of the tip, at distances [from, to] from it, nearer to it than
// to any other tip the same part reaches, and not flank damage.
std::vector<std::size_t> ring_points(const CrackAngleLattice& l, const std::vector<std::vector<std::size_t>>& parts,
                                     const std::vector<char>& in_precrack, const std::vector<Vector2>& tips,
                                     std::size_t t, const TipRing& ring, double attach) {
  std::vector<std::size_t> ring_members;
  for (const auto& part : parts) {
    const std::vector<std::size_t> reached = tips_reached(l, part, tips, attach);
    if (std::find(reached.begin(), reached.end(), t) == reached.end()) continue;
    for (std::size_t i : part) {
      const double distance = (position_of(l, i) - ring.tip).norm();
      if (in_precrack[i] || distance < ring.from || distance > ring.to) continue;
      const bool nearest = std::none_of(reached.begin(), reached.end(), [&](std::size_t o) {
        return o != t && (position_of(l, i) - tips[o]).norm() < distance;
      });
      if (nearest && !on_flank(ring, position_of(l, i))) ring_members.push_back(i);
    }
  }
  std::sort(ring_members.begin(), ring_members.end());
  return ring_members;
}

// Whether the crack leaving the tip reaches the outer radius: a connected part of the new crack
// points (not pre-crack, not flank damage, nearer to this tip than to any other) that comes
// within the attach radius of the tip and has a point at `to` or beyond. Linked through new
// points only: damage that spreads from elsewhere along the pre-crack (at a notch mouth, say)
// is not the crack leaving the tip.
bool crack_reaches_outer_radius(const CrackAngleLattice& l, const std::vector<std::size_t>& new_crack,
                                const std::vector<Vector2>& tips, const TipRing& ring, double attach, double link) {
  std::vector<std::size_t> members;
  for (std::size_t i : new_crack) {
    const Vector2 p = position_of(l, i);
    const double distance = (p - ring.tip).norm();
    const bool nearest =
        std::none_of(tips.begin(), tips.end(), [&](const Vector2& other) { return (p - other).norm() < distance; });
    if (nearest && !on_flank(ring, p)) members.push_back(i);
  }
  const auto distance = [&](std::size_t i) { return (position_of(l, i) - ring.tip).norm(); };
  for (const auto& part : connected_parts(l, members, link))
    if (std::any_of(part.begin(), part.end(), [&](std::size_t i) { return distance(i) <= attach; }) &&
        std::any_of(part.begin(), part.end(), [&](std::size_t i) { return distance(i) >= ring.to; }))
      return true;
  return false;
}

// The cracks of one tip: each connected part of its ring points at least 3 dx long along its
// fitted line, oriented away from the tip, by increasing signed angle.
std::vector<CrackAngle> cracks_of_ring(const CrackAngleLattice& l, const std::vector<std::size_t>& members,
                                       const TipRing& ring, double spacing) {
  std::vector<CrackAngle> cracks;
  for (const auto& part : connected_parts(l, members, kLinkRadiusInSpacings * spacing)) {
    const LineFit fit = fit_line(l, part);
    if (fit.s_max - fit.s_min < kMinimumCrackExtentInSpacings * spacing) continue;
    const Vector2 u = (fit.centroid - ring.tip).dot(fit.axis) >= 0 ? fit.axis : Vector2(-fit.axis);
    const Vector2& d = ring.direction;
    double angle = std::atan2(d.x() * u.y() - d.y() * u.x(), d.dot(u)) * 180.0 / std::numbers::pi;
    if (angle <= -180.0) angle += 360.0;
    CrackAngle crack;
    crack.signed_angle_deg = angle;
    crack.angle_deg = std::fabs(angle);
    crack.fit_point = {fit.centroid.x(), fit.centroid.y(), l.z[part.front()]};
    crack.fit_direction = {u.x(), u.y(), 0.0};
    crack.points = part.size();
    cracks.push_back(crack);
  }
  std::sort(cracks.begin(), cracks.end(),
            [](const CrackAngle& a, const CrackAngle& b) { return a.signed_angle_deg < b.signed_angle_deg; });
  return cracks;
}

void check_lattice(const CrackAngleLattice& l, const std::vector<double>& first, const CrackAngleSettings& s,
                   double from, double to) {
  const std::size_t n = l.x.size();
  if (l.y.size() != n || l.z.size() != n || l.include.size() != n || l.near_boundary.size() != n || first.size() != n)
    throw std::invalid_argument("measure_crack_angles: arrays of different lengths");
  if (!(s.spacing > 0) || !(s.horizon > 0))
    throw std::invalid_argument("measure_crack_angles: spacing and horizon must be positive");
  if (!(from >= 0) || !(to > from)) throw std::invalid_argument("measure_crack_angles: bad range");
}

// The tips of the result: given, or found on the pre-crack (with notes when there are none).
std::vector<CrackTipSpec> choose_tips(const CrackAngleLattice& l, const std::vector<std::size_t>& precrack,
                                      const CrackAngleSettings& settings, std::vector<std::string>& notes) {
  if (!settings.tips.empty()) return settings.tips;
  if (precrack.empty()) {
    notes.push_back("no pre-crack in the first snapshot: give the tips with --crack-tip and --crack-direction");
    return {};
  }
  std::vector<CrackTipSpec> tips = tips_of_precrack(l, precrack, settings, notes);
  if (tips.empty())
    notes.push_back(
        "the pre-crack has no tip (each part reaches the free surface at both ends or is too short): give "
        "the tips with --crack-tip and --crack-direction");
  return tips;
}

std::string time_in_us(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", seconds * 1e6);
  return buffer;
}

// The measurement of one tip on the snapshot it is (so far) taken from.
struct TipMeasurement {
  bool measured = false;
  double time = 0;
  bool reached_outer_radius = false;
  std::vector<CrackAngle> cracks;
};

}  // namespace

struct CrackAngleTracker::State {
  const CrackAngleLattice lattice;
  CrackAngleSettings settings;
  CrackAngleResult base;  // tips, range, notes about the tips
  std::vector<std::size_t> precrack;
  std::vector<char> in_precrack;
  std::vector<Vector2> tip_positions;
  std::vector<TipRing> rings;
  std::vector<TipMeasurement> measurements;
};

CrackAngleTracker::CrackAngleTracker(const CrackAngleLattice& l, const std::vector<double>& first_damage,
                                     const CrackAngleSettings& settings)
    : state_(std::make_unique<State>(State{l, settings, {}, {}, {}, {}, {}, {}})) {
  State& s = *state_;
  const double delta = settings.horizon;
  s.base.range_from = settings.range_from.value_or(kDefaultRangeFromInHorizons * delta);
  s.base.range_to = settings.range_to.value_or(kDefaultRangeToInHorizons * delta);
  check_lattice(l, first_damage, settings, s.base.range_from, s.base.range_to);
  s.precrack = crack_points(l.include, first_damage, settings.damage_threshold);
  s.in_precrack.assign(l.x.size(), 0);
  for (std::size_t i : s.precrack) s.in_precrack[i] = 1;
  s.base.tips = choose_tips(l, s.precrack, settings, s.base.notes);
  for (const auto& tip : s.base.tips) {
    TipRing ring{planar(tip.position), planar(tip.direction).normalized(), s.base.range_from, s.base.range_to};
    ring.flank_width = notch_half_gap(l, ring.tip, ring.direction, delta, ring.to) + delta;
    s.tip_positions.push_back(ring.tip);
    s.rings.push_back(ring);
  }
  s.measurements.resize(s.base.tips.size());
}

CrackAngleTracker::~CrackAngleTracker() = default;

bool CrackAngleTracker::settled() const {
  return std::all_of(state_->measurements.begin(), state_->measurements.end(),
                     [](const TipMeasurement& m) { return m.reached_outer_radius; });
}

void CrackAngleTracker::add_frame(double time, const std::vector<double>& damage) {
  State& s = *state_;
  const CrackAngleLattice& l = s.lattice;
  if (damage.size() != l.x.size()) throw std::invalid_argument("measure_crack_angles: arrays of different lengths");
  if (settled()) return;
  // The crack of this snapshot, the pre-crack included, and its connected parts.
  const std::vector<std::size_t> crack = crack_points(l.include, damage, s.settings.damage_threshold);
  std::vector<std::size_t> all_crack;  // damage never heals; the union is for safety
  std::set_union(crack.begin(), crack.end(), s.precrack.begin(), s.precrack.end(), std::back_inserter(all_crack));
  const double link = kLinkRadiusInSpacings * s.settings.spacing;
  const auto parts = connected_parts(l, all_crack, link);
  std::vector<std::size_t> new_crack;
  std::set_difference(crack.begin(), crack.end(), s.precrack.begin(), s.precrack.end(), std::back_inserter(new_crack));
  const double attach = kAttachRadiusInHorizons * s.settings.horizon;
  for (std::size_t t = 0; t < s.rings.size(); ++t) {
    TipMeasurement& m = s.measurements[t];
    if (m.reached_outer_radius) continue;
    const auto members = ring_points(l, parts, s.in_precrack, s.tip_positions, t, s.rings[t], attach);
    const bool reached = crack_reaches_outer_radius(l, new_crack, s.tip_positions, s.rings[t], attach, link);
    m = {true, time, reached, cracks_of_ring(l, members, s.rings[t], s.settings.spacing)};
  }
}

CrackAngleResult CrackAngleTracker::result() const {
  const State& s = *state_;
  CrackAngleResult result = s.base;
  for (std::size_t t = 0; t < s.rings.size(); ++t) {
    const TipMeasurement& m = s.measurements[t];
    if (!m.measured) continue;
    if (m.cracks.empty())
      result.notes.push_back("no crack leaves the tip at " + point_in_mm(s.rings[t].tip) + " between " +
                             millimetres(s.rings[t].from) + " and " + millimetres(s.rings[t].to) +
                             " mm from it (at t = " + time_in_us(m.time) + " us)");
    for (std::size_t c = 0; c < m.cracks.size(); ++c) {
      CrackAngle crack = m.cracks[c];
      crack.tip_index = t;
      crack.crack_index = c;
      crack.tip = result.tips[t];
      crack.measured_at_s = m.time;
      crack.reached_outer_radius = m.reached_outer_radius;
      result.cracks.push_back(crack);
    }
  }
  return result;
}

CrackAngleResult measure_crack_angles(const CrackAngleLattice& lattice, const std::vector<double>& first_damage,
                                      const std::vector<double>& damage, const CrackAngleSettings& settings,
                                      double time) {
  CrackAngleTracker tracker(lattice, first_damage, settings);
  tracker.add_frame(time, damage);
  return tracker.result();
}

namespace {

Vector3 parse_tip(const std::string& text) {
  const auto items = split_commas(text);
  const std::string expected = " (expected X,Y or X,Y,Z: lengths such as 50mm,20mm; plain numbers are metres)";
  if (items.size() < 2 || items.size() > 3)
    throw InputError("--crack-tip '" + text + "': " + std::to_string(items.size()) + " coordinates" + expected);
  Vector3 tip{};
  for (std::size_t k = 0; k < items.size(); ++k) try {
      tip[k] = parse_quantity_as(items[k], dim::length);
    } catch (const std::invalid_argument& e) {
      throw InputError("--crack-tip '" + text + "': " + e.what() + expected);
    }
  return tip;
}

// An angle in the x-y plane from +x, counter-clockwise, with its unit ("0deg", "1.2rad"), or
// a vector DX,DY[,DZ] of plain numbers.
Vector3 parse_direction(const std::string& text) {
  const std::string expected =
      " (expected an angle in the x-y plane from +x, counter-clockwise, with its unit, such as 0deg or "
      "1.2rad, or a vector DX,DY[,DZ] of plain numbers)";
  const auto items = split_commas(text);
  Vector3 v{};
  try {
    if (items.size() == 1) {
      const Quantity q = parse_quantity(items[0]);
      if (!q.dimension.is_angle) throw std::invalid_argument("\"" + items[0] + "\" is not an angle with a unit");
      v = {std::cos(q.value), std::sin(q.value), 0.0};
    } else if (items.size() <= 3) {
      for (std::size_t k = 0; k < items.size(); ++k) v[k] = parse_quantity_as(items[k], dim::none);
    } else {
      throw std::invalid_argument(std::to_string(items.size()) + " components");
    }
  } catch (const std::invalid_argument& e) {
    throw InputError("--crack-direction '" + text + "': " + e.what() + expected);
  }
  const double norm = std::hypot(v[0], v[1], v[2]);
  if (!(norm > 0) || !std::isfinite(norm))
    throw InputError("--crack-direction '" + text + "': a zero vector has no direction" + expected);
  for (double& c : v) c /= norm;
  return v;
}

void parse_range(const std::string& text, CrackAngleSettings& settings) {
  const std::string expected = " (expected FROM,TO: two lengths with 0 <= FROM < TO, such as 5mm,30mm)";
  const auto items = split_commas(text);
  if (items.size() != 2)
    throw InputError("--crack-angle-range '" + text + "': " + std::to_string(items.size()) + " values" + expected);
  double from = 0, to = 0;
  try {
    from = parse_quantity_as(items[0], dim::length);
    to = parse_quantity_as(items[1], dim::length);
  } catch (const std::invalid_argument& e) {
    throw InputError("--crack-angle-range '" + text + "': " + e.what() + expected);
  }
  if (!(from >= 0) || !(to > from))
    throw InputError("--crack-angle-range '" + text + "': FROM must be at least 0 and below TO" + expected);
  settings.range_from = from;
  settings.range_to = to;
}

void parse_measure_time(const std::string& text, CrackAngleSettings& settings) {
  const std::string expected =
      " (expected a time with its unit, such as 40us; the angle is measured on the last "
      "snapshot at or before it)";
  double time = 0;
  try {
    time = parse_quantity_as(text, dim::time);
  } catch (const std::invalid_argument& e) {
    throw InputError("--crack-angle-time '" + text + "': " + e.what() + expected);
  }
  if (!std::isfinite(time) || time < 0)
    throw InputError("--crack-angle-time '" + text + "': a negative time" + expected);
  settings.measure_time = time;
}

}  // namespace

void parse_crack_angle_options(const CrackAngleOptionTexts& texts, CrackAngleSettings& settings) {
  if (texts.range) parse_range(*texts.range, settings);
  if (texts.time) parse_measure_time(*texts.time, settings);
  if (texts.tips.empty() && texts.directions.empty()) return;
  if (texts.tips.empty()) throw InputError("--crack-direction needs --crack-tip (the tip it starts from)");
  if (texts.directions.empty())
    throw InputError("--crack-tip needs --crack-direction (the pre-crack direction at that tip)");
  if (texts.directions.size() != 1 && texts.directions.size() != texts.tips.size())
    throw InputError("--crack-direction is given " + std::to_string(texts.directions.size()) + " times for " +
                     std::to_string(texts.tips.size()) + " --crack-tip (give it once for all tips, or once per tip)");
  settings.tips.clear();
  for (std::size_t k = 0; k < texts.tips.size(); ++k)
    settings.tips.push_back(
        {parse_tip(texts.tips[k]), parse_direction(texts.directions[texts.directions.size() == 1 ? 0 : k])});
}

void check_crack_tips_in_body(const std::vector<CrackTipSpec>& tips, const std::vector<double>& x,
                              const std::vector<double>& y, const std::vector<double>& z,
                              const std::vector<char>& include, double margin) {
  Vector3 low{}, high{};
  low.fill(std::numeric_limits<double>::infinity());
  high.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < x.size(); ++i)
    if (include[i])
      for (int k = 0; k < 3; ++k) {
        const double c = k == 0 ? x[i] : (k == 1 ? y[i] : z[i]);
        low[k] = std::min(low[k], c);
        high[k] = std::max(high[k], c);
      }
  const bool planar_body = low[2] == high[2];
  const auto range = [&](int k) { return millimetres(low[k]) + " to " + millimetres(high[k]) + " mm"; };
  const std::string box = "x " + range(0) + ", y " + range(1) + (planar_body ? std::string() : ", z " + range(2));
  for (const auto& tip : tips) {
    const Vector3& p = tip.position;
    const std::string name =
        "--crack-tip (" + millimetres(p[0]) + ", " + millimetres(p[1]) + ", " + millimetres(p[2]) + ") mm";
    if (planar_body && (p[2] != low[2] || tip.direction[2] != 0))
      throw InputError(name + ": the run is 2-D (z = " + millimetres(low[2]) +
                       " mm): give the tip and the direction in the x-y plane");
    for (int k = 0; k < 3; ++k)
      if (p[k] < low[k] - margin || p[k] > high[k] + margin)
        throw InputError(name + " lies outside the body (" + box + "); lengths without a unit are metres");
  }
}

}  // namespace mppm::post
