// The crack angle on synthetic 2-D damage fields with known angles: a crack leaving a straight
// pre-crack at +30, -70 and 90 degrees; the Kalthoff-Winkler layout (two notches, one crack
// each); a crack branched at the tip; damage along the notch flanks only (no crack), next to a
// real crack and next to a crack running back at 150 degrees; an interior pre-crack (two tips)
// and one through the body (none); a notch cut out of the body with the tip and direction
// given; a series in which the angle is taken on the snapshot where the crack crosses the ring;
// the parsing of the options; a 3-D run measured on its mid-thickness layer.
//
// Tolerance of an angle: the points of a crack band are the lattice points within dx of the
// crack line, so either end of the fitted stretch may sit up to about one dx off the line:
// atan(dx / L), L the length of the stretch fitted (the ring, cut by the plate's edge).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "postprocess/crack_angle.hpp"
#include "postprocess/crack_metrics.hpp"
#include "postprocess/mid_thickness_layer.hpp"

namespace {

using mppm::post::CrackAngleLattice;
using mppm::post::CrackAngleOptionTexts;
using mppm::post::CrackAngleResult;
using mppm::post::CrackAngleSettings;
using mppm::post::CrackAngleTracker;
using mppm::post::measure_crack_angles;

constexpr double kDegree = std::numbers::pi / 180.0;

struct Segment {
  double x0, y0, x1, y1;
};

// A segment of `length` from (x0, y0) at `angle_deg` from +x.
Segment ray(double x0, double y0, double angle_deg, double length) {
  return {x0, y0, x0 + length * std::cos(angle_deg * kDegree), y0 + length * std::sin(angle_deg * kDegree)};
}

double distance_to(const Segment& s, double px, double py) {
  const double ux = s.x1 - s.x0, uy = s.y1 - s.y0;
  if (ux == 0 && uy == 0) return std::hypot(px - s.x0, py - s.y0);  // a point: the centre of a disc
  const double t = std::clamp(((px - s.x0) * ux + (py - s.y0) * uy) / (ux * ux + uy * uy), 0.0, 1.0);
  return std::hypot(px - s.x0 - t * ux, py - s.y0 - t * uy);
}

// A rectangular 2-D lattice of spacing dx with points at (i + 1/2) dx, (j + 1/2) dx.
struct Plate {
  double dx, horizon;
  std::vector<double> x, y, z;
  std::vector<char> include;
  std::vector<char> near_boundary;

  Plate(double width, double height, double spacing, double horizon_factor)
      : dx(spacing), horizon(horizon_factor * spacing) {
    const int nx = static_cast<int>(std::lround(width / dx)), ny = static_cast<int>(std::lround(height / dx));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        x.push_back((i + 0.5) * dx);
        y.push_back((j + 0.5) * dx);
        z.push_back(0.0);
        include.push_back(1);
      }
    update_surface();
  }
  // Removes (excludes) the points within `half_width` of a segment: a notch cut out of the body.
  void cut(const Segment& notch, double half_width) {
    for (std::size_t i = 0; i < x.size(); ++i)
      if (distance_to(notch, x[i], y[i]) < half_width) include[i] = 0;
    update_surface();
  }
  // The free-surface mask as the crack tracker computes it.
  void update_surface() {
    mppm::post::CrackSettings settings;
    settings.spacing = dx;
    settings.horizon = horizon;
    near_boundary = mppm::post::CrackTracker(x, y, z, include, settings).near_boundary();
  }
  // Damage 0.45 (above the 0.35 threshold) within `half_width` of the segments, 0.2 elsewhere.
  std::vector<double> damage(const std::vector<Segment>& crack, double half_width) const {
    std::vector<double> d(x.size(), 0.2);
    for (std::size_t i = 0; i < x.size(); ++i)
      for (const auto& s : crack)
        if (distance_to(s, x[i], y[i]) <= half_width * (1 + 1e-9)) d[i] = 0.45;
    return d;
  }
  CrackAngleLattice lattice() const { return {x, y, z, include, near_boundary}; }
  CrackAngleSettings settings() const {
    CrackAngleSettings s;
    s.spacing = dx;
    s.horizon = horizon;
    return s;
  }
};

// The crack-branching plate (workflows/crack-branching): 100 x 40 mm, dx 0.5 mm, delta 4.05 dx,
// pre-crack from the left edge to the centre.
constexpr double kDx = 0.5e-3;
const Segment kPrecrack{0.0, 0.02, 0.05, 0.02};

CrackAngleResult measure_on_branching_plate(const std::vector<Segment>& grown, double flank_half_width = 0) {
  const Plate plate(0.1, 0.04, kDx, 4.05);
  std::vector<Segment> last = grown;
  last.push_back(kPrecrack);
  std::vector<double> last_damage = plate.damage(last, kDx);
  if (flank_half_width > 0) {
    const auto flanks = plate.damage({kPrecrack}, flank_half_width);
    for (std::size_t i = 0; i < last_damage.size(); ++i) last_damage[i] = std::max(last_damage[i], flanks[i]);
  }
  return measure_crack_angles(plate.lattice(), plate.damage({kPrecrack}, kDx), last_damage, plate.settings());
}

// The default ring of the branching plate: 2 to 12 horizons.
constexpr double kFrom = 2 * 4.05 * kDx, kTo = 12 * 4.05 * kDx;

double tolerance_deg(double fitted_length, double dx = kDx) { return std::atan(dx / fitted_length) / kDegree; }

TEST(PostCrackAngle, CrackLeavingAStraightPrecrack) {
  // Angle, and the length of crack inside the plate (the -70 and 90 degree cracks reach the
  // bottom and top edges, 20 mm from the notch line).
  struct Case {
    double angle_deg, length;
  };
  for (const Case c : {Case{30.0, 0.03}, Case{-70.0, 0.02 / std::sin(70 * kDegree)}, Case{90.0, 0.02}}) {
    const auto result = measure_on_branching_plate({ray(0.05, 0.02, c.angle_deg, c.length)});
    ASSERT_EQ(result.tips.size(), 1u) << c.angle_deg;
    // The tip is the end of the pre-crack band's axis: the last damaged column, within dx of
    // the notch end; the direction is +x (the band is symmetric about y = 20 mm).
    EXPECT_NEAR(result.tips[0].position[0], 0.05, kDx);
    EXPECT_NEAR(result.tips[0].position[1], 0.02, 1e-9);
    EXPECT_NEAR(result.tips[0].direction[0], 1.0, 1e-12);
    ASSERT_EQ(result.cracks.size(), 1u) << c.angle_deg;
    const auto& crack = result.cracks[0];
    const double fitted = std::min(kTo, c.length) - kFrom;
    EXPECT_NEAR(crack.signed_angle_deg, c.angle_deg, tolerance_deg(fitted)) << c.angle_deg;
    EXPECT_DOUBLE_EQ(crack.angle_deg, std::fabs(crack.signed_angle_deg));
    EXPECT_NEAR(std::atan2(crack.fit_direction[1], crack.fit_direction[0]) / kDegree, crack.signed_angle_deg, 1e-9);
    EXPECT_GT(crack.points, 20u);
    EXPECT_TRUE(result.notes.empty()) << result.notes.front();
  }
}

TEST(PostCrackAngle, KalthoffWinklerTwoNotchesOneCrackEach) {
  // The specimen: 100 mm along the notches by 200 mm along the struck edge, dx 1 mm, delta
  // 3.015 dx; notches from the left edge at y = 75 and 125 mm, 50 mm long; from each tip a crack
  // at 65 degrees away from the struck block (down from the lower notch, up from the upper one),
  // 40 mm long: past the default ring's 12 horizons, short of the edges 75 mm away.
  const double dx = 1e-3;
  const Plate plate(0.1, 0.2, dx, 3.015);
  const Segment lower{0.0, 0.075, 0.05, 0.075}, upper{0.0, 0.125, 0.05, 0.125};
  const double length = 0.04;
  const auto first = plate.damage({lower, upper}, dx);
  const auto last = plate.damage({lower, upper, ray(0.05, 0.075, -65, length), ray(0.05, 0.125, 65, length)}, dx);
  const auto result = measure_crack_angles(plate.lattice(), first, last, plate.settings());
  ASSERT_EQ(result.tips.size(), 2u);
  EXPECT_NEAR(result.tips[0].position[1], 0.075, 1e-9);  // bottom to top
  EXPECT_NEAR(result.tips[1].position[1], 0.125, 1e-9);
  ASSERT_EQ(result.cracks.size(), 2u);
  const double tolerance = tolerance_deg(12 * plate.horizon - 2 * plate.horizon, dx);
  EXPECT_EQ(result.cracks[0].tip_index, 0u);
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, -65.0, tolerance);
  EXPECT_EQ(result.cracks[1].tip_index, 1u);
  EXPECT_NEAR(result.cracks[1].signed_angle_deg, 65.0, tolerance);
  for (const auto& crack : result.cracks) EXPECT_NEAR(crack.angle_deg, 65.0, tolerance);
}

TEST(PostCrackAngle, InteriorPrecrackHasTwoTipsAndACrackThroughTheBodyNone) {
  // A pre-crack from x = 30 to 60 mm inside the plate: a tip at each end, pointing outward, in
  // the order of x (same y); a crack leaves each at 140 degrees from +x on the left end (-40 to
  // that tip's direction, -x) and at 40 degrees on the right end.
  const Plate plate(0.1, 0.04, kDx, 4.05);
  const Segment interior{0.03, 0.02, 0.06, 0.02};
  const auto first = plate.damage({interior}, kDx);
  auto result = measure_crack_angles(
      plate.lattice(), first, plate.damage({interior, ray(0.03, 0.02, 140, 0.025), ray(0.06, 0.02, 40, 0.025)}, kDx),
      plate.settings());
  ASSERT_EQ(result.tips.size(), 2u);
  EXPECT_NEAR(result.tips[0].position[0], 0.03, kDx);
  EXPECT_NEAR(result.tips[0].direction[0], -1.0, 1e-12);
  EXPECT_NEAR(result.tips[1].position[0], 0.06, kDx);
  EXPECT_NEAR(result.tips[1].direction[0], 1.0, 1e-12);
  ASSERT_EQ(result.cracks.size(), 2u);
  const double tolerance = tolerance_deg(kTo - kFrom);
  EXPECT_EQ(result.cracks[0].tip_index, 0u);
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, -40.0, tolerance);
  EXPECT_EQ(result.cracks[1].tip_index, 1u);
  EXPECT_NEAR(result.cracks[1].signed_angle_deg, 40.0, tolerance);

  // A pre-crack from edge to edge has no tip; a note says so.
  const Segment through{0.0, 0.02, 0.1, 0.02};
  result = measure_crack_angles(plate.lattice(), plate.damage({through}, kDx), plate.damage({through}, kDx),
                                plate.settings());
  EXPECT_TRUE(result.tips.empty());
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("the pre-crack has no tip"), std::string::npos) << result.notes[0];
}

TEST(PostCrackAngle, CrackBranchedAtTheTipGivesTwoAngles) {
  // Branches at +20 and -35 degrees, 25 mm long: 2 delta from the tip they are 7 dx apart,
  // two connected parts of the ring. Ordered by signed angle.
  const auto result = measure_on_branching_plate({ray(0.05, 0.02, 20, 0.025), ray(0.05, 0.02, -35, 0.025)});
  ASSERT_EQ(result.cracks.size(), 2u);
  const double tolerance = tolerance_deg(kTo - kFrom);
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, -35.0, tolerance);
  EXPECT_NEAR(result.cracks[1].signed_angle_deg, 20.0, tolerance);
  EXPECT_EQ(result.cracks[0].crack_index, 0u);
  EXPECT_EQ(result.cracks[1].crack_index, 1u);
  EXPECT_EQ(result.cracks[0].tip_index, result.cracks[1].tip_index);
}

TEST(PostCrackAngle, DamageAlongTheNotchFlanksIsNotACrack) {
  // The flanks of the notch damaged 3 dx to each side (the pre-crack band is 1 dx), plus a blob
  // of one horizon around the tip: nothing leaves the tip, and a note says so.
  const Plate plate(0.1, 0.04, kDx, 4.05);
  auto last = plate.damage({kPrecrack}, 3 * kDx);
  const auto blob = plate.damage({{0.05, 0.02, 0.05, 0.02}}, plate.horizon);
  for (std::size_t i = 0; i < last.size(); ++i) last[i] = std::max(last[i], blob[i]);
  const auto result = measure_crack_angles(plate.lattice(), plate.damage({kPrecrack}, kDx), last, plate.settings());
  ASSERT_EQ(result.tips.size(), 1u);
  EXPECT_TRUE(result.cracks.empty()) << result.cracks.front().signed_angle_deg;
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("no crack leaves the tip"), std::string::npos) << result.notes[0];
}

TEST(PostCrackAngle, FlankDamageBesideARealCrack) {
  // The same flank damage with a crack at +30 degrees: one crack, at 30 degrees.
  auto result = measure_on_branching_plate({ray(0.05, 0.02, 30, 0.03)}, 3 * kDx);
  ASSERT_EQ(result.cracks.size(), 1u);
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, 30.0, tolerance_deg(kTo - kFrom));
  // A crack really leaving the tip backwards, at 150 degrees, is reported: only its part within
  // the flank width (delta + the half-gap of dx/2) of the notch line is left out, i.e. its
  // first 2 (delta + dx/2) from the tip.
  result = measure_on_branching_plate({ray(0.05, 0.02, 150, 0.03)}, 3 * kDx);
  ASSERT_EQ(result.cracks.size(), 1u);
  const double fitted = kTo - 2 * (4.05 * kDx + kDx / 2);
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, 150.0, tolerance_deg(fitted));
}

TEST(PostCrackAngle, NotchCutOutOfTheBodyWithTheTipGiven) {
  // The notch is a gap in the lattice, 6 mm wide with a round end (no damage at the start);
  // the crack leaves its tip at -60 degrees and damage grows along both faces of the gap, the
  // first two rows, 3.25 and 3.75 mm from the notch line: farther than one horizon (2.025 mm),
  // so the flank width must include the gap's half width (3.25 mm) measured on the lattice.
  Plate plate(0.1, 0.04, kDx, 4.05);
  plate.cut(kPrecrack, 3e-3);
  const auto first = plate.damage({}, kDx);
  const Segment face_below{0.0, 0.02 - 3.5e-3, 0.05, 0.02 - 3.5e-3};
  const Segment face_above{0.0, 0.02 + 3.5e-3, 0.05, 0.02 + 3.5e-3};
  const auto last = plate.damage({ray(0.05, 0.02, -60, 0.02), face_below, face_above}, kDx);

  // Without the tip there is nothing to measure from.
  auto result = measure_crack_angles(plate.lattice(), first, last, plate.settings());
  EXPECT_TRUE(result.tips.empty());
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("--crack-tip"), std::string::npos) << result.notes[0];

  CrackAngleSettings settings = plate.settings();
  mppm::post::parse_crack_angle_options({{"50mm,20mm"}, {"0deg"}, std::nullopt}, settings);
  result = measure_crack_angles(plate.lattice(), first, last, settings);
  ASSERT_EQ(result.tips.size(), 1u);
  ASSERT_EQ(result.cracks.size(), 1u);
  const double fitted = 0.02 / std::sin(60 * kDegree) - kFrom;  // reaches the bottom edge
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, -60.0, tolerance_deg(fitted));
  EXPECT_DOUBLE_EQ(result.range_from, kFrom);
  EXPECT_DOUBLE_EQ(result.range_to, kTo);

  // A ring of 5 to 15 mm: the same angle, from fewer points.
  const std::size_t points = result.cracks[0].points;
  mppm::post::parse_crack_angle_options({{"0.05,0.02"}, {"1,0"}, "5mm,15mm"}, settings);
  result = measure_crack_angles(plate.lattice(), first, last, settings);
  ASSERT_EQ(result.cracks.size(), 1u);
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, -60.0, tolerance_deg(0.01));
  EXPECT_LT(result.cracks[0].points, points);
  EXPECT_DOUBLE_EQ(result.range_from, 5e-3);
}

// A series on the crack-branching plate with a ring of 4 to 15 mm: a crack grows from the tip at
// 60 degrees, 8 mm long at 1 us, 16 mm (past the ring) at 2 us; at 3 us a disc of damage 13 mm
// around the tip (the crushing of a struck block, say) swamps the ring.
struct GrowingCrackSeries {
  const Plate plate{0.1, 0.04, kDx, 4.05};
  CrackAngleSettings settings = plate.settings();
  std::vector<double> precrack = plate.damage({kPrecrack}, kDx);
  GrowingCrackSeries() {
    settings.range_from = 4e-3;
    settings.range_to = 15e-3;
  }
  std::vector<double> crack(double length) const { return plate.damage({kPrecrack, ray(0.05, 0.02, 60, length)}, kDx); }
  std::vector<double> crack_and_disc() const {
    auto d = crack(0.016);
    const auto disc = plate.damage({{0.05, 0.02, 0.05, 0.02}}, 13e-3);
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::max(d[i], disc[i]);
    return d;
  }
};

TEST(PostCrackAngle, MeasuredWhenTheCrackCrossesTheRing) {
  const GrowingCrackSeries series;
  CrackAngleTracker tracker(series.plate.lattice(), series.precrack, series.settings);
  tracker.add_frame(0.0, series.precrack);
  tracker.add_frame(1e-6, series.crack(0.008));
  EXPECT_FALSE(tracker.settled());
  tracker.add_frame(2e-6, series.crack(0.016));
  EXPECT_TRUE(tracker.settled());
  tracker.add_frame(3e-6, series.crack_and_disc());
  const auto result = tracker.result();
  ASSERT_EQ(result.cracks.size(), 1u);
  const auto& crack = result.cracks[0];
  EXPECT_NEAR(crack.signed_angle_deg, 60.0, tolerance_deg(15e-3 - 4e-3));
  EXPECT_DOUBLE_EQ(crack.measured_at_s, 2e-6);
  EXPECT_TRUE(crack.reached_outer_radius);
  EXPECT_TRUE(result.notes.empty()) << result.notes.front();

  // On the last snapshot the disc fills the ring: one part, far from 60 degrees (what the
  // series rule avoids).
  const auto last =
      measure_crack_angles(series.plate.lattice(), series.precrack, series.crack_and_disc(), series.settings, 3e-6);
  ASSERT_FALSE(last.cracks.empty());
  EXPECT_GT(std::fabs(last.cracks[0].signed_angle_deg - 60.0), 10.0) << last.cracks[0].signed_angle_deg;
  EXPECT_TRUE(last.cracks[0].reached_outer_radius);  // the crack past 15 mm is in it
}

TEST(PostCrackAngle, CrackShortOfTheRingIsMeasuredOnTheLastSnapshot) {
  // The crack stops at 12 mm, short of the 15 mm outer radius: the last snapshot, not reached.
  const GrowingCrackSeries series;
  CrackAngleTracker tracker(series.plate.lattice(), series.precrack, series.settings);
  for (const auto& [time, length] : {std::pair{1e-6, 0.006}, std::pair{2e-6, 0.012}, std::pair{3e-6, 0.012}})
    tracker.add_frame(time, series.crack(length));
  EXPECT_FALSE(tracker.settled());
  const auto result = tracker.result();
  ASSERT_EQ(result.cracks.size(), 1u);
  EXPECT_NEAR(result.cracks[0].signed_angle_deg, 60.0, tolerance_deg(12e-3 - 4e-3));
  EXPECT_DOUBLE_EQ(result.cracks[0].measured_at_s, 3e-6);
  EXPECT_FALSE(result.cracks[0].reached_outer_radius);

  // Damage spreading along the notch from its mouth, 50 mm behind the tip and linked to the tip
  // only through the pre-crack, is not the crack leaving the tip: still not reached.
  auto with_mouth = series.crack(0.012);
  const auto mouth = series.plate.damage({{0.0, 0.02, 0.0, 0.02}}, 8e-3);
  for (std::size_t i = 0; i < with_mouth.size(); ++i) with_mouth[i] = std::max(with_mouth[i], mouth[i]);
  tracker.add_frame(4e-6, with_mouth);
  EXPECT_FALSE(tracker.settled());
  EXPECT_DOUBLE_EQ(tracker.result().cracks.at(0).measured_at_s, 4e-6);
}

TEST(PostCrackAngle, OptionsParse) {
  CrackAngleSettings settings;
  mppm::post::parse_crack_angle_options({{"50mm,20mm", "0.1,0.02,0"}, {"90deg", "-1,1"}, "2mm, 3 cm", "40us"},
                                        settings);
  ASSERT_EQ(settings.tips.size(), 2u);
  EXPECT_DOUBLE_EQ(settings.tips[0].position[0], 0.05);
  EXPECT_DOUBLE_EQ(settings.tips[0].position[1], 0.02);
  EXPECT_NEAR(settings.tips[0].direction[0], 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(settings.tips[0].direction[1], 1.0);
  EXPECT_DOUBLE_EQ(settings.tips[1].position[0], 0.1);
  EXPECT_DOUBLE_EQ(settings.tips[1].direction[0], -std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(*settings.range_from, 2e-3);
  EXPECT_DOUBLE_EQ(*settings.range_to, 3e-2);
  EXPECT_DOUBLE_EQ(*settings.measure_time, 40e-6);
  // One direction for every tip.
  mppm::post::parse_crack_angle_options({{"1mm,2mm", "3mm,4mm"}, {"180deg"}, std::nullopt}, settings);
  ASSERT_EQ(settings.tips.size(), 2u);
  EXPECT_DOUBLE_EQ(settings.tips[1].direction[0], -1.0);
}

// The option's error message names the option and says what was expected.
void expect_error(const CrackAngleOptionTexts& texts, const std::string& expected) {
  CrackAngleSettings settings;
  try {
    mppm::post::parse_crack_angle_options(texts, settings);
    ADD_FAILURE() << "no error; expected one containing: " << expected;
  } catch (const mppm::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(PostCrackAngle, BadOptionsAreRefusedWithTheReason) {
  expect_error({{"50mm"}, {"0deg"}, std::nullopt}, "--crack-tip '50mm': 1 coordinates (expected X,Y or X,Y,Z");
  expect_error({{"50mm,20mm,1mm,2mm"}, {"0deg"}, std::nullopt}, "4 coordinates");
  expect_error({{"50mm,abc"}, {"0deg"}, std::nullopt}, "--crack-tip '50mm,abc': \"abc\" is not a number");
  expect_error({{"50mm,20 N"}, {"0deg"}, std::nullopt}, "expected a length");
  expect_error({{"50mm,20mm"}, {"30"}, std::nullopt}, "--crack-direction '30': \"30\" is not an angle with a unit");
  expect_error({{"50mm,20mm"}, {"0,0"}, std::nullopt}, "a zero vector has no direction");
  expect_error({{"50mm,20mm"}, {"1mm,0"}, std::nullopt}, "--crack-direction '1mm,0'");
  expect_error({{"50mm,20mm"}, {"5mm"}, std::nullopt}, "is not an angle with a unit");
  expect_error({{"50mm,20mm"}, {}, std::nullopt}, "--crack-tip needs --crack-direction");
  expect_error({{}, {"0deg"}, std::nullopt}, "--crack-direction needs --crack-tip");
  expect_error({{"1mm,1mm", "2mm,2mm", "3mm,3mm"}, {"0deg", "90deg"}, std::nullopt},
               "--crack-direction is given 2 times for 3 --crack-tip");
  expect_error({{}, {}, "5mm"}, "--crack-angle-range '5mm': 1 values (expected FROM,TO");
  expect_error({{}, {}, "30mm,5mm"}, "FROM must be at least 0 and below TO");
  expect_error({{}, {}, "-1mm,5mm"}, "FROM must be at least 0 and below TO");
  expect_error({{}, {}, "5mm,30 us"}, "expected a length");
  expect_error({{}, {}, std::nullopt, "40mm"},
               "--crack-angle-time '40mm': \"40mm\" is a length (e.g. m, mm), expected a time");
  expect_error({{}, {}, std::nullopt, "soon"}, "--crack-angle-time 'soon': \"soon\" is not a number");
  expect_error({{}, {}, std::nullopt, "-5us"}, "--crack-angle-time '-5us': a negative time (expected a time");
}

// 3-D runs: the angle on the mid-thickness layer (postprocess/mid_thickness_layer.hpp). A plate of
// the 2-D lattice repeated over `planes` lattice planes z = (k + 1/2) dx, with a layer of
// non-body points (a boundary layer) below and above.
struct LayeredPlate {
  Plate plate;
  int planes;
  std::vector<double> x, y, z;
  std::vector<char> body;

  LayeredPlate(const Plate& p, int n) : plate(p), planes(n) {
    for (int k = -1; k <= n; ++k)
      for (std::size_t i = 0; i < p.x.size(); ++i) {
        x.push_back(p.x[i]);
        y.push_back(p.y[i]);
        z.push_back((k + 0.5) * p.dx + (i % 3 == 0 ? 1e-12 : 0.0));  // rounding of the lattice
        body.push_back(k >= 0 && k < n ? 1 : 0);
      }
  }
  std::size_t plane_of(std::size_t point) const { return point / plate.x.size(); }  // 0: the layer below
  // The damage of plane k from `plane_damage(k)` (a 2-D field), 0 on the boundary layers.
  template <typename PlaneDamage>
  std::vector<double> damage(PlaneDamage&& plane_damage) const {
    std::vector<double> d(x.size(), 0.0);
    for (int k = 0; k < planes; ++k) {
      const auto field = plane_damage(k);
      std::copy(field.begin(), field.end(), d.begin() + static_cast<std::ptrdiff_t>((k + 1) * plate.x.size()));
    }
    return d;
  }
};

TEST(PostCrackAngle, MidThicknessLayerIsTheMiddlePlaneOrTheLowerOfTheTwo) {
  const Plate plate(0.01, 0.01, 1e-3, 3.05);
  for (int planes : {5, 4, 1}) {
    const LayeredPlate layered(plate, planes);
    const auto layer = mppm::post::mid_thickness_layer(layered.z, layered.body, 1e-3);
    const int expected = planes == 4 ? 1 : planes / 2;  // of planes 1 and 2 of four, the lower
    EXPECT_NEAR(layer.z, (expected + 0.5) * 1e-3, 1e-11) << planes << " planes";
    EXPECT_EQ(layer.points, plate.x.size()) << planes << " planes";
    for (std::size_t i = 0; i < layered.z.size(); ++i) {
      ASSERT_EQ(layer.include[i] != 0, layered.plane_of(i) == static_cast<std::size_t>(expected + 1)) << i;
      ASSERT_EQ(layer.flat_z[i], layer.z);
    }
  }
  EXPECT_THROW(mppm::post::mid_thickness_layer({0.0}, {1, 1}, 1e-3), std::invalid_argument);
  EXPECT_THROW(mppm::post::mid_thickness_layer({0.0, 1.0}, {0, 0}, 1e-3), std::invalid_argument);
  EXPECT_THROW(mppm::post::mid_thickness_layer({0.0}, {1}, 0.0), std::invalid_argument);
}

TEST(PostCrackAngle, ThreeDimensionalRunIsMeasuredOnItsMidThicknessLayer) {
  // 80 x 80 mm, dx 1 mm, delta 3.05 dx; an edge pre-crack along y = 40 mm to x = 40 mm through
  // every plane. On the middle plane a crack leaves the tip at 60 degrees, on the others at 20:
  // the angle is the middle plane's. Five planes (the middle one) and four (the lower middle one).
  const double dx = 1e-3;
  const Plate plate(0.08, 0.08, dx, 3.05);
  const Segment notch{0.0, 0.04, 0.04001, 0.04};
  const double length = 0.03;
  for (int planes : {5, 4}) {
    const LayeredPlate layered(plate, planes);
    const auto layer = mppm::post::mid_thickness_layer(layered.z, layered.body, dx);
    const int middle = planes == 4 ? 1 : planes / 2;
    const auto first = layered.damage([&](int) { return plate.damage({notch}, dx); });
    const auto last = layered.damage([&](int k) {
      return plate.damage({notch, ray(0.04001, 0.04, k == middle ? 60 : 20, length)}, dx);
    });
    mppm::post::CrackSettings settings;
    settings.spacing = dx;
    settings.horizon = plate.horizon;
    const mppm::post::CrackTracker tracker(layered.x, layered.y, layer.flat_z, layer.include, settings);
    const CrackAngleLattice lattice{layered.x, layered.y, layer.flat_z, layer.include, tracker.near_boundary()};
    const auto result = measure_crack_angles(lattice, first, last, plate.settings());
    ASSERT_EQ(result.tips.size(), 1u) << planes << " planes";
    EXPECT_NEAR(result.tips[0].position[2], layer.z, 1e-12);
    ASSERT_EQ(result.cracks.size(), 1u) << planes << " planes";
    EXPECT_NEAR(result.cracks[0].signed_angle_deg, 60.0, tolerance_deg(12 * plate.horizon - 2 * plate.horizon, dx))
        << planes << " planes";
  }
}

}  // namespace
