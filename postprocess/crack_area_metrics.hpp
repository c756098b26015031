// Crack metrics of 3-D damage runs (docs/stages.md "Metrics", postprocess/README.md "3-D crack
// metrics"): the crack area, its start time and the front's furthest advance, from the
// `crack_area` field of the snapshots, each point's share of the crack surface its broken bonds
// span (solver/crack_area.hpp, docs/theory.md section 7). The crack area of a frame is the sum of
// the field over the body points; the first frame's is the pre-crack's (its cut bonds), and the
// new crack is the area grown since. Crack points are the body points holding at least
// kCrackFrontPointCells dx^2 of crack area; the front advance is their largest distance from the
// crack points of the first frame (the pre-crack), or, without a pre-crack, of the first frame
// that has any. Streaming (one frame at a time): a series never holds more than one field.
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mppm::post {

// The crack has started once the new area reaches this many dx^2: one lattice cell's face, the
// smallest crack surface the lattice resolves (the bonds crossing it all broken); a lone broken bond
// spans 0.09 dx^2 or less (horizon factor 2.05 or more).
inline constexpr double kCrackStartCells = 1.0;
// A body point belongs to the crack when it holds at least this many dx^2 of crack area: the row
// of points on either face of a crack normal to a lattice axis holds 0.46 dx^2 per point at
// horizon factor 2.05, 0.34 at 3.05, 0.28 at 4.05 (the next rows 0.05, 0.16, 0.16); a point with
// one or two stray broken bonds holds 0.09 dx^2 or less.
inline constexpr double kCrackFrontPointCells = 0.125;

struct CrackAreaFrame {
  double time = 0.0;
  double total_area = 0.0;  // [m^2], the pre-crack's included
  double new_area = 0.0;    // [m^2] grown since the first frame
  std::size_t crack_points = 0;
  std::optional<double> front_advance;  // [m]; none before there is a crack to measure from
};

struct CrackAreaMetrics {
  double precrack_area_m2 = 0.0;  // the first frame's crack area
  double area_m2 = 0.0;           // the new crack area of the last frame
  std::optional<double> start_time_s;
  std::optional<double> front_advance_m;  // the largest over the frames
  std::optional<double> front_advance_time_s;
  std::vector<CrackAreaFrame> frames;
  std::vector<std::string> notes;
};

class CrackAreaTracker {
 public:
  // x, y, z: reference positions [m]; include: nonzero for body points (not layers); spacing: dx.
  CrackAreaTracker(std::vector<double> x, std::vector<double> y, std::vector<double> z, std::vector<char> include,
                   double spacing);
  ~CrackAreaTracker();
  CrackAreaTracker(const CrackAreaTracker&) = delete;
  CrackAreaTracker& operator=(const CrackAreaTracker&) = delete;

  // Frames in increasing time; crack_area per point [m^2].
  void add_frame(double time, const std::vector<double>& crack_area);
  CrackAreaMetrics finish() const;

  double start_area() const { return kCrackStartCells * spacing_ * spacing_; }
  double front_point_area() const { return kCrackFrontPointCells * spacing_ * spacing_; }

 private:
  void set_reference(const std::vector<std::size_t>& crack_points, double time);
  double distance_to_reference(std::size_t i) const;

  std::vector<double> x_, y_, z_;
  std::vector<char> include_;
  double spacing_ = 0.0;
  std::vector<char> in_reference_;
  std::vector<std::size_t> reference_;
  class Grid;
  std::unique_ptr<Grid> grid_;    // over the reference points
  std::vector<double> distance_;  // per point, from the reference; NaN until needed
  CrackAreaMetrics metrics_;
};

// The same, for a whole series at once (tests).
CrackAreaMetrics measure_crack_area(const std::vector<double>& x, const std::vector<double>& y,
                                    const std::vector<double>& z, const std::vector<char>& include,
                                    const std::vector<double>& times, const std::vector<std::vector<double>>& areas,
                                    double spacing);

// crack_area.csv of the post directory: time_s, crack_area_m2 (new), total_crack_area_m2,
// crack_front_advance_m (empty before there is a crack to measure from), one row per frame.
std::string crack_area_csv(const CrackAreaMetrics& metrics);

}  // namespace mppm::post
