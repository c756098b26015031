// The pore-pressure metrics of summary.json (postprocess/pore_pressure_metrics.*) on synthetic
// frames: the extremes over time and points with their time and place, the last frame's
// extremes and volume-weighted mean, and the fictitious layers left out.
#include <gtest/gtest.h>

#include "postprocess/pore_pressure_metrics.hpp"

namespace mppm::post {
namespace {

// Four points on the x axis at 0, 1, 2, 3 mm with volumes 1, 1, 2, 4; the last is a layer point.
Snapshot reference() {
  Snapshot r;
  r.point_count = 4;
  SnapshotField position{"position", 3, {0, 0, 0, 1e-3, 0, 0, 2e-3, 0, 0, 3e-3, 0, 0}};
  SnapshotField volume{"volume", 1, {1, 1, 2, 4}};
  SnapshotField region{"region", 1, {0, 0, 0, 1}};
  r.fields = {position, volume, region};
  return r;
}

TEST(PostPorePressure, ExtremesOverTimeAndTheLastFrame) {
  PorePressureTracker tracker(reference());
  EXPECT_FALSE(tracker.result());
  tracker.add_frame(0.0, {0.0, 0.0, 0.0, 9e9});     // the layer's value never counts
  tracker.add_frame(1e-6, {5e3, -2e3, 1e3, -9e9});  // the peak, at x = 0
  tracker.add_frame(2e-6, {1e3, -4e3, 2e3, 0.0});   // the suction, at x = 1 mm
  const auto m = tracker.result();
  ASSERT_TRUE(m);
  EXPECT_EQ(m->peak.value, 5e3);
  EXPECT_EQ(m->peak.time, 1e-6);
  EXPECT_EQ(m->peak.position[0], 0.0);
  EXPECT_EQ(m->minimum.value, -4e3);
  EXPECT_EQ(m->minimum.time, 2e-6);
  EXPECT_EQ(m->minimum.position[0], 1e-3);
  EXPECT_EQ(m->final_max, 2e3);
  EXPECT_EQ(m->final_min, -4e3);
  EXPECT_DOUBLE_EQ(m->final_mean, (1e3 * 1 - 4e3 * 1 + 2e3 * 2) / 4.0);
  EXPECT_EQ(m->final_time, 2e-6);
}

}  // namespace
}  // namespace mppm::post
