// Pore-pressure metrics (see pore_pressure_metrics.hpp).
#include "postprocess/pore_pressure_metrics.hpp"

#include <stdexcept>

namespace mppm::post {

PorePressureTracker::PorePressureTracker(const Snapshot& reference) {
  const SnapshotField* position = reference.find("position");
  const SnapshotField* volume = reference.find("volume");
  const SnapshotField* region = reference.find("region");
  if (!position || !volume || !region) throw std::invalid_argument("PorePressureTracker: incomplete reference");
  position_ = position->data;
  volume_ = volume->data;
  for (std::size_t i = 0; i < region->data.size(); ++i)
    if (region->data[i] == 0.0) body_.push_back(i);
}

void PorePressureTracker::add_frame(double time, const std::vector<double>& pressure) {
  if (body_.empty()) return;
  auto at = [&](std::size_t i) {
    return PressureExtreme{pressure[i], time, {position_[3 * i], position_[3 * i + 1], position_[3 * i + 2]}};
  };
  std::size_t high = body_.front(), low = body_.front();
  double weighted = 0.0, volume = 0.0;
  for (const std::size_t i : body_) {
    if (pressure[i] > pressure[high]) high = i;
    if (pressure[i] < pressure[low]) low = i;
    weighted += volume_[i] * pressure[i];
    volume += volume_[i];
  }
  if (!metrics_) metrics_ = PorePressureMetrics{at(high), at(low)};
  if (pressure[high] > metrics_->peak.value) metrics_->peak = at(high);
  if (pressure[low] < metrics_->minimum.value) metrics_->minimum = at(low);
  metrics_->final_max = pressure[high];
  metrics_->final_min = pressure[low];
  metrics_->final_mean = weighted / volume;
  metrics_->final_time = time;
}

std::optional<PorePressureMetrics> PorePressureTracker::result() const { return metrics_; }

}  // namespace mppm::post
