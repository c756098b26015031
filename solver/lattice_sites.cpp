// The site map of a regular lattice (lattice_sites.hpp).
#include "solver/lattice_sites.hpp"

#include <algorithm>
#include <limits>

namespace mppm::solver {

namespace {

// A point within this fraction of a spacing of a site is on it. Rounding of coordinates is many
// orders below; a jittered or non-lattice cloud is far above.
constexpr double site_tolerance = 1e-2;
// A box of more sites per point is a sparse body (a ring, a thin shell): its map would outweigh the
// cell grid.
constexpr std::int64_t most_sites_per_point = 16;

// The offsets whose site can hold a point within `reach` of a point on a site: every point lies
// within site_tolerance spacings of its site, so a bonded pair's offset is at most
// reach / spacing + 2 sqrt(D) site_tolerance long.
std::vector<std::array<int, 3>> candidate_offsets(int dimension, double reach_in_spacings) {
  const double longest = reach_in_spacings + 2.0 * std::sqrt(static_cast<double>(dimension)) * site_tolerance;
  const int n = static_cast<int>(std::ceil(longest));
  std::vector<std::array<int, 3>> out;
  const int nz = dimension == 3 ? n : 0;
  for (int c = -nz; c <= nz; ++c)
    for (int b = -n; b <= n; ++b)
      for (int a = -n; a <= n; ++a) {
        const double length2 = static_cast<double>(a * a + b * b + c * c);
        if ((a != 0 || b != 0 || c != 0) && length2 <= longest * longest) out.push_back({a, b, c});
      }
  return out;
}

}  // namespace

std::optional<LatticeSites> lattice_sites(const PointPositions& points, double spacing, double reach) {
  const int D = points.dimension;
  const std::size_t n = points.count;
  if (n == 0 || !(spacing > 0.0) || n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    return std::nullopt;
  LatticeSites l;
  l.dimension = D;
  l.spacing = spacing;
  const double* x = points.position;
  for (int a = 0; a < D; ++a) {
    l.low[a] = x[a];
    for (std::size_t i = 1; i < n; ++i) l.low[a] = std::min(l.low[a], x[i * D + a]);
  }
  // Every point on a site, and the box of the sites (a site index beyond 2^50, or a coordinate
  // that is not a number, is no lattice of ours: the tests are written to fail on NaN).
  std::array<std::int64_t, 3> top{0, 0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < D; ++a) {
      const double q = (x[i * D + a] - l.low[a]) / spacing;
      if (!(q <= 0x1.0p50)) return std::nullopt;
      const auto k = std::llround(q);
      if (!(std::abs(x[i * D + a] - l.low[a] - static_cast<double>(k) * spacing) <= site_tolerance * spacing))
        return std::nullopt;
      top[a] = std::max<std::int64_t>(top[a], k);
    }
  std::int64_t total = 1;
  for (int a = 0; a < D; ++a) {
    l.sites[a] = top[a] + 1;
    total *= l.sites[a];
    if (total > most_sites_per_point * static_cast<std::int64_t>(n) + 1024) return std::nullopt;
  }
  l.point_at.assign(static_cast<std::size_t>(total), -1);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = l.site_of(&x[i * D]);
    std::int64_t site = 0;
    for (int a = D - 1; a >= 0; --a) site = site * l.sites[a] + k[a];
    auto& slot = l.point_at[static_cast<std::size_t>(site)];
    if (slot >= 0) return std::nullopt;  // two points on one site
    slot = static_cast<std::int32_t>(i);
  }
  l.candidates = candidate_offsets(D, reach / spacing);
  return l;
}

}  // namespace mppm::solver
