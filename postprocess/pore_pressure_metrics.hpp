// Pore-pressure metrics of a pore-fluid run for summary.json (postprocess/README.md): the highest
// and lowest pressure of the body over all snapshots (where and when), and the last snapshot's
// highest, lowest and volume-weighted mean pressure. The fictitious layers (region > 0) carry no
// fluid and are left out.
#pragma once
#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "common/snapshot_file.hpp"

namespace mppm::post {

struct PressureExtreme {
  double value = 0.0;                             // [Pa], compression positive
  double time = 0.0;                              // [s]
  std::array<double, 3> position{0.0, 0.0, 0.0};  // reference position [m]
};

struct PorePressureMetrics {
  PressureExtreme peak;                                       // the highest pressure
  PressureExtreme minimum;                                    // the lowest (negative: suction)
  double final_max = 0.0, final_min = 0.0, final_mean = 0.0;  // of the last snapshot [Pa]
  double final_time = 0.0;
};

class PorePressureTracker {
 public:
  // From the reference snapshot (position, volume, region).
  explicit PorePressureTracker(const Snapshot& reference);
  // One snapshot's pressure field (one value per point), in time order.
  void add_frame(double time, const std::vector<double>& pressure);
  // Empty when no frame was added.
  std::optional<PorePressureMetrics> result() const;

 private:
  std::vector<std::size_t> body_;  // the body points
  std::vector<double> position_, volume_;
  std::optional<PorePressureMetrics> metrics_;
};

}  // namespace mppm::post
