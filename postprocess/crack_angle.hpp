// The crack angle of docs/stages.md "Metrics": the angle between each crack that leaves a
// pre-crack tip and the pre-crack direction (Kalthoff-Winkler: ~60-70 degrees; the crack
// branching plate: ~0 before it branches). The method is postprocess/README.md "Crack angle":
// - tips and directions: from the pre-crack (the crack path of the first snapshot: damage >=
//   the threshold), one principal axis per connected part, an end of the axis away from the free
//   surface is a tip; or given (--crack-tip, --crack-direction) for notches cut out of the body;
// - per tip, the crack points of one snapshot that are new, connected to the tip, in a ring of
//   distances [from, to] around it and not on the notch flanks; each connected part of them long
//   enough is one crack, fitted by a straight line (total least squares);
// - the snapshot: per tip, the first in which its crack reaches the outer radius `to` (later,
//   damage spreading around the tip would swamp the crack path), else the last one; or the last
//   one at or before a given time.
// Measured in the x-y plane: on the body of a 2-D run, and on the mid-thickness layer of a 3-D run
// (mid_thickness_layer.hpp; the driver, postprocess_run.cpp, picks the layer).
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mppm::post {

using Vector3 = std::array<double, 3>;

// A pre-crack tip: its position [m] and the unit direction of the pre-crack past it (from the
// pre-crack into the body).
struct CrackTipSpec {
  Vector3 position{};
  Vector3 direction{};
};

struct CrackAngleSettings {
  double spacing = 0.0;            // dx [m]
  double horizon = 0.0;            // delta [m]
  double damage_threshold = 0.35;  // crack path: damage >= this (as the crack tracker)
  // Ring of distances from the tip [m]; unset: 2 delta and 12 delta.
  std::optional<double> range_from, range_to;
  std::vector<CrackTipSpec> tips;  // given tips; empty: found on the pre-crack
  // Measure on the last snapshot at or before this time [s] instead of the first where the
  // crack reaches `to` (the driver picks that snapshot; see CrackAngleTracker).
  std::optional<double> measure_time;
};

// The lattice the angles are measured on: positions [m] (z zero in 2-D), the body points
// (nonzero; layers excluded) and the body points within 2 dx of the free surface
// (CrackTracker::near_boundary()).
struct CrackAngleLattice {
  const std::vector<double>& x;
  const std::vector<double>& y;
  const std::vector<double>& z;
  const std::vector<char>& include;
  const std::vector<char>& near_boundary;
};

// One crack leaving one tip.
struct CrackAngle {
  std::size_t tip_index = 0;    // into CrackAngleResult::tips
  std::size_t crack_index = 0;  // among the cracks of this tip (by increasing signed angle)
  CrackTipSpec tip;
  double signed_angle_deg = 0;  // from the pre-crack direction to the crack, counter-clockwise positive, (-180, 180]
  double angle_deg = 0;         // |signed_angle_deg|
  Vector3 fit_point{};          // the centroid of the points fitted [m]
  Vector3 fit_direction{};      // unit, pointing away from the tip
  std::size_t points = 0;       // crack points fitted
  double measured_at_s = 0;     // time of the snapshot measured [s]
  bool reached_outer_radius = false;  // the tip's crack reached `to` on that snapshot
};

struct CrackAngleResult {
  std::vector<CrackTipSpec> tips;  // in the order of the output (see measure_crack_angles)
  std::vector<CrackAngle> cracks;  // by tip, then by increasing signed angle
  double range_from = 0, range_to = 0;
  std::vector<std::string> notes;  // tips without a crack, pre-crack parts without a tip, ...
};

// The crack angles of a snapshot series, fed one snapshot at a time (in time order). The tips
// come from the first snapshot's damage (the pre-crack) or the settings. Each added snapshot is
// measured for the tips whose crack has not yet reached the outer radius: a tip keeps the first
// measurement in which it did, else the last one added. Tips found on the pre-crack are ordered
// by y, then x (bottom to top); given tips keep their order. Throws std::invalid_argument on
// arrays of different lengths or a bad setting. `lattice`'s arrays must outlive the tracker.
class CrackAngleTracker {
 public:
  CrackAngleTracker(const CrackAngleLattice& lattice, const std::vector<double>& first_damage,
                    const CrackAngleSettings& settings);
  ~CrackAngleTracker();
  CrackAngleTracker(const CrackAngleTracker&) = delete;
  CrackAngleTracker& operator=(const CrackAngleTracker&) = delete;

  // Measures the unsettled tips on the damage of the snapshot at `time` [s].
  void add_frame(double time, const std::vector<double>& damage);
  // Every tip's crack has reached the outer radius (or there is no tip): later snapshots change
  // nothing.
  bool settled() const;
  // The cracks of every tip on its snapshot (none before the first add_frame).
  CrackAngleResult result() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Crack angles between the first snapshot's damage (the pre-crack) and one later snapshot's,
// taken at `time` (a CrackAngleTracker fed that snapshot only).
CrackAngleResult measure_crack_angles(const CrackAngleLattice& lattice, const std::vector<double>& first_damage,
                                      const std::vector<double>& damage, const CrackAngleSettings& settings,
                                      double time = 0.0);

// The command-line options of the crack angle, as typed.
struct CrackAngleOptionTexts {
  std::vector<std::string> tips;                   // --crack-tip X,Y[,Z] (repeatable)
  std::vector<std::string> directions;             // --crack-direction ANGLE | DX,DY[,DZ] (once, or once per tip)
  std::optional<std::string> range;                // --crack-angle-range FROM,TO
  std::optional<std::string> time = std::nullopt;  // --crack-angle-time T
};

// Parses them into `settings` (tips, range, measure time). Throws InputError naming the option, the value and
// what was expected.
void parse_crack_angle_options(const CrackAngleOptionTexts& texts, CrackAngleSettings& settings);

// Given tips must lie within the bounding box of the body points (`include` nonzero), grown by
// `margin`, and in the x-y plane in a 2-D run. Throws InputError naming the tip and the box.
void check_crack_tips_in_body(const std::vector<CrackTipSpec>& tips, const std::vector<double>& x,
                              const std::vector<double>& y, const std::vector<double>& z,
                              const std::vector<char>& include, double margin);

}  // namespace mppm::post
