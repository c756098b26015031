// Crack metrics of docs/stages.md "Metrics": crack start, branching and end times, the largest tip
// speed and the grown crack length, from the damage field of a snapshot series.
// Crack path = points with damage >= 0.35 (kCrackDamageThreshold, docs/theory.md section 7). The
// pre-crack is the cracked set of the first frame (a run directory does not carry the notch
// geometry). Frames come from the snapshots' damage fields (add_frame) or from the solver's
// crack-arrival table (add_cracked_frame, crack_path_table.hpp).
// Tips: cracked points connected to the pre-crack whose path length along the crack (shortest
// path through cracked points) is a local maximum within one horizon, clustered so that tips
// closer than 2 horizons are one tip. Streaming (one frame at a time) so a million-point series
// never holds more than one damage field.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "common/crack_path.hpp"

namespace mppm::post {

struct CrackSettings {
  double spacing = 0.0;                             // dx [m]
  double horizon = 0.0;                             // delta [m]
  double damage_threshold = kCrackDamageThreshold;  // crack path: damage >= this
  double stop_duration_s = 5e-6;                    // "every tip stops for 5 us"
  // Derived lengths (docs/stages.md): start when the leading tip advanced 2 dx; branching needs two
  // tips more than 2 delta apart; a tip "reaches a boundary" within 2 dx of it.
};

struct CrackTip {
  double x = 0, y = 0, z = 0;
  double path_length = 0;  // along the crack from the pre-crack [m]
};

struct CrackFrame {
  double time = 0;
  std::size_t cracked_points = 0;
  double lead_path_length = 0;  // largest path length of any cracked point [m]
  double crack_length = 0;      // grown crack: union of the tip paths [m]
  std::vector<CrackTip> tips;   // tips that advanced at least 2 delta
  bool tip_at_boundary = false;
};

struct CrackMetrics {
  std::optional<double> start_time_s;
  std::optional<double> branch_time_s;
  std::optional<double> end_time_s;
  std::string end_reason;  // "tip reached a boundary" | "tips stopped for ..." | ""
  std::optional<double> tip_speed_max_m_per_s;
  std::optional<double> crack_length_m;  // grown length at the end (or last snapshot)
  std::vector<CrackFrame> frames;
  std::string note;
};

class CrackTracker {
 public:
  // x, y, z: positions [m] (z zero in 2-D); include: nonzero for body points (not layers).
  CrackTracker(std::vector<double> x, std::vector<double> y, std::vector<double> z, std::vector<char> include,
               const CrackSettings& settings);

  // Frames in increasing time. The first frame's cracked set is the pre-crack.
  void add_frame(double time, const std::vector<double>& damage);
  // The same with the crack path given as its points (any order; points that are not body points
  // are left out, as add_frame leaves them out): the frames of the crack-arrival table.
  void add_cracked_frame(double time, const std::vector<std::size_t>& cracked);

  CrackMetrics finish() const;
  // The damage at and above which a body point belongs to the crack path.
  double damage_threshold() const { return settings_.damage_threshold; }
  // Per point: a body point within 2 dx of the body's free surface (the crack angle's tips).
  const std::vector<char>& near_boundary() const { return near_boundary_; }

 private:
  std::vector<double> x_, y_, z_;
  std::vector<char> include_;
  std::vector<char> near_boundary_;  // within 2 dx of the body's free surface
  void add_frame_of_nodes(double time, const std::vector<std::size_t>& nodes);
  CrackSettings settings_;
  std::vector<std::size_t> precrack_;
  bool have_reference_ = false;
  double reference_time_ = 0;
  std::vector<CrackFrame> frames_;
};

// The same, for a whole series at once (tests, small runs).
CrackMetrics measure_crack(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
                           const std::vector<char>& include, const std::vector<double>& times,
                           const std::vector<std::vector<double>>& damage, const CrackSettings& settings);

}  // namespace mppm::post
