// Piecewise-linear time histories of boundary values (docs/theory.md section 8).
#include <algorithm>
#include <cstddef>

#include "common/scene.hpp"

namespace mppm {

std::vector<double> History::at(double t) const {
  std::vector<double> out(values.empty() ? 0 : values.front().size());
  for (std::size_t c = 0; c < out.size(); ++c) out[c] = component_at(t, c);
  return out;
}

double History::component_at(double t, std::size_t c) const {
  if (times.empty()) return 0.0;
  if (t <= times.front()) return values.front()[c];
  if (t >= times.back()) return values.back()[c];
  // Times are non-decreasing; a repeated time is a jump, and the later row applies from it on.
  const auto upper = std::upper_bound(times.begin(), times.end(), t);
  const std::size_t k = static_cast<std::size_t>(upper - times.begin());  // times[k-1] <= t < times[k]
  const double t0 = times[k - 1], t1 = times[k];
  const double v0 = values[k - 1][c], v1 = values[k][c];
  if (t1 <= t0) return v1;
  return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
}

}  // namespace mppm
