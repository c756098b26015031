// A uniform bucket grid over a point set, for fixed-radius neighbour queries in the metrics
// (crack tip tracking, boundary-layer masks). Built once per query set, no allocation per query.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mppm::post {

// Positions are structure-of-arrays (x, y, z; 2-D sets pass z all zero).
class PointGrid {
 public:
  // Indexes the points listed in `members` (indices into x/y/z); `cell` > 0 is the bucket size,
  // best equal to the largest query radius.
  PointGrid(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
            const std::vector<std::size_t>& members, double cell);

  // Calls visit(j) for every indexed point j with |x_j - p| <= radius (including p itself).
  template <class Visit>
  void for_each_within(double px, double py, double pz, double radius, Visit&& visit) const;

 private:
  std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const { return (k * ny_ + j) * nx_ + i; }
  const std::vector<double>& x_;
  const std::vector<double>& y_;
  const std::vector<double>& z_;
  double cell_ = 1.0;
  double x0_ = 0.0, y0_ = 0.0, z0_ = 0.0;
  std::int64_t nx_ = 1, ny_ = 1, nz_ = 1;
  std::vector<std::size_t> start_;  // CSR over cells: start_[c] .. start_[c+1]
  std::vector<std::size_t> points_;
};

template <class Visit>
void PointGrid::for_each_within(double px, double py, double pz, double radius, Visit&& visit) const {
  if (points_.empty()) return;
  const double r2 = radius * radius;
  auto range = [&](double p, double origin, std::int64_t n, std::int64_t& lo, std::int64_t& hi) {
    lo = static_cast<std::int64_t>((p - radius - origin) / cell_);
    hi = static_cast<std::int64_t>((p + radius - origin) / cell_);
    if (p - radius - origin < 0) lo = 0;
    if (lo < 0) lo = 0;
    if (hi > n - 1) hi = n - 1;
  };
  std::int64_t i0, i1, j0, j1, k0, k1;
  range(px, x0_, nx_, i0, i1);
  range(py, y0_, ny_, j0, j1);
  range(pz, z0_, nz_, k0, k1);
  for (std::int64_t k = k0; k <= k1; ++k)
    for (std::int64_t j = j0; j <= j1; ++j)
      for (std::int64_t i = i0; i <= i1; ++i) {
        const auto c = static_cast<std::size_t>(key(i, j, k));
        for (std::size_t s = start_[c]; s < start_[c + 1]; ++s) {
          const std::size_t q = points_[s];
          const double dx = x_[q] - px, dy = y_[q] - py, dz = z_[q] - pz;
          if (dx * dx + dy * dy + dz * dz <= r2) visit(q);
        }
      }
}

}  // namespace mppm::post
