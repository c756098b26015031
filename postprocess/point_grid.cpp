// Bucket grid construction (counting sort of the members into cells).
#include "postprocess/point_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mppm::post {

PointGrid::PointGrid(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
                     const std::vector<std::size_t>& members, double cell)
    : x_(x), y_(y), z_(z), cell_(cell) {
  if (!(cell > 0.0)) throw std::invalid_argument("PointGrid: cell size must be positive");
  if (members.empty()) {
    start_.assign(2, 0);
    return;
  }
  double lo[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                  std::numeric_limits<double>::max()};
  double hi[3] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
                  std::numeric_limits<double>::lowest()};
  for (std::size_t m : members) {
    const double p[3] = {x[m], y[m], z[m]};
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  }
  x0_ = lo[0];
  y0_ = lo[1];
  z0_ = lo[2];
  auto count = [&](int c) { return static_cast<std::int64_t>(std::floor((hi[c] - lo[c]) / cell)) + 1; };
  nx_ = count(0);
  ny_ = count(1);
  nz_ = count(2);
  auto cell_of = [&](std::size_t m) {
    const auto i = std::min<std::int64_t>(static_cast<std::int64_t>((x[m] - x0_) / cell), nx_ - 1);
    const auto j = std::min<std::int64_t>(static_cast<std::int64_t>((y[m] - y0_) / cell), ny_ - 1);
    const auto k = std::min<std::int64_t>(static_cast<std::int64_t>((z[m] - z0_) / cell), nz_ - 1);
    return static_cast<std::size_t>(key(i, j, k));
  };
  const auto cells = static_cast<std::size_t>(nx_ * ny_ * nz_);
  start_.assign(cells + 1, 0);
  for (std::size_t m : members) ++start_[cell_of(m) + 1];
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  points_.resize(members.size());
  std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t m : members) points_[fill[cell_of(m)]++] = m;
}

}  // namespace mppm::post
