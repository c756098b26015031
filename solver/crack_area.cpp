// The crack area of the broken bonds (crack_area.hpp; docs/theory.md section 7, "Crack area").
#include "solver/crack_area.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mppm::solver {

namespace {

// The mean of |e . n| over the directions n, for a unit vector e: 1/2 in 3-D, 2/pi in 2-D.
double mean_projection(int dimension) { return dimension == 3 ? 0.5 : 2.0 / std::numbers::pi; }

// The cut neighbours of point i: [begin, end) into cuts.neighbor (empty when i lost none).
std::pair<std::int64_t, std::int64_t> cut_range(const PrecrackCutBonds& cuts, std::size_t i) {
  const auto it = std::lower_bound(cuts.points.begin(), cuts.points.end(), i);
  if (it == cuts.points.end() || *it != i) return {0, 0};
  const auto k = static_cast<std::size_t>(it - cuts.points.begin());
  return {cuts.offset[k], cuts.offset[k + 1]};
}

// Calls visit(V_j, xi_ij, broken) for every bond of point i's family before the first break: its
// list (broken entries included), then its pre-crack cuts, in that fixed order.
template <class Visit>
void for_each_initial_bond(const PointData& p, const BondFamilies& f, const PrecrackCutBonds& cuts, std::size_t i,
                           Visit&& visit) {
  const int D = p.dimension;
  double xi[3] = {0.0, 0.0, 0.0};
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    bond_vector(f, p, i, b, xi);
    visit(p.volume[f.neighbor_of(b)], xi, !f.acting(b));
  }
  const auto [first, last] = cut_range(cuts, i);
  for (std::int64_t k = first; k < last; ++k) {
    const auto j = static_cast<std::size_t>(cuts.neighbor[static_cast<std::size_t>(k)]);
    for (int a = 0; a < D; ++a)
      xi[a] = cuts.xi.empty() ? p.position[j * D + a] - p.position[i * D + a]
                              : cuts.xi[static_cast<std::size_t>(k) * D + a];
    visit(p.volume[j], xi, true);
  }
}

}  // namespace

PrecrackCutBonds record_cut_bonds(const BondFamilies& f) {
  PrecrackCutBonds cuts;
  const int D = f.dimension;
  for (std::size_t i = 0; i + 1 < f.offset.size(); ++i) {
    const std::size_t before = cuts.neighbor.size();
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const auto entry = static_cast<std::size_t>(b);
      if (f.acting(b)) continue;
      cuts.neighbor.push_back(static_cast<std::int32_t>(f.neighbor_of(b)));
      if (!f.xi.empty()) cuts.xi.insert(cuts.xi.end(), f.xi.begin() + entry * D, f.xi.begin() + (entry + 1) * D);
    }
    if (cuts.neighbor.size() == before) continue;
    if (cuts.offset.empty()) cuts.offset.push_back(0);
    cuts.points.push_back(i);
    cuts.offset.push_back(static_cast<std::int64_t>(cuts.neighbor.size()));
  }
  return cuts;
}

double point_crack_area(const PointData& p, const BondFamilies& f, const PrecrackCutBonds& cuts, std::size_t i) {
  const int D = p.dimension;
  // The broken bonds: their volume, their volume-weighted length and their volume-weighted sum.
  double broken = 0.0, length = 0.0, side[3] = {0.0, 0.0, 0.0};
  for_each_initial_bond(p, f, cuts, i, [&](double v, const double* xi, bool is_broken) {
    if (!is_broken) return;
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) {
      side[a] += v * xi[a];
      r2 += xi[a] * xi[a];
    }
    broken += v;
    length += v * std::sqrt(r2);
  });
  if (broken == 0.0) return 0.0;
  double norm2 = 0.0;
  for (int a = 0; a < D; ++a) norm2 += side[a] * side[a];
  const double norm = std::sqrt(norm2);
  const bool directed = norm >= kCrackAreaDirectedShare * length;
  // sum_j V_j |xi . n| over the whole initial family: the bonds per unit area that a plane of
  // normal n through the point's neighbourhood crosses, times 2 V_i (docs/theory.md section 7).
  double crossing = 0.0;
  for_each_initial_bond(p, f, cuts, i, [&](double v, const double* xi, bool) {
    double projection = 0.0, r2 = 0.0;
    for (int a = 0; a < D; ++a) {
      projection += xi[a] * side[a];
      r2 += xi[a] * xi[a];
    }
    crossing += v * (directed ? std::fabs(projection) / norm : mean_projection(D) * std::sqrt(r2));
  });
  return crossing > 0.0 ? p.volume[i] * broken / crossing : 0.0;
}

}  // namespace mppm::solver
