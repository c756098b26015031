// Calibration, no-fail zone, damage field and shape-tensor refresh of the damage effect.
#include "solver/bond_breakage.hpp"

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <numbers>

#include "solver/shape_tensor.hpp"

namespace mppm::solver {

double critical_bond_work(int dimension, double g_cr, double horizon, double thickness) {
  // Sum of V_i V_j w_cr over the bonds that cross a unit area of a plane, in the continuum limit:
  // 3-D pi delta^4 / 4 w_cr per unit area; 2-D (2/3) delta^3 t^2 w_cr per unit length, i.e.
  // (2/3) delta^3 t w_cr per unit area of the slice.
  if (dimension == 3) return 4.0 * g_cr / (std::numbers::pi * horizon * horizon * horizon * horizon);
  return 3.0 * g_cr / (2.0 * thickness * horizon * horizon * horizon);
}

void mark_no_fail_zone(PointData& p, double depth) {
  std::fill(p.no_fail.begin(), p.no_fail.end(), 0);
  if (!(depth > 0.0)) return;
  // Nearest boundary point by a k-d tree (CGAL), in 3-D coordinates (z = 0 in 2-D).
  using Kernel = CGAL::Simple_cartesian<double>;
  using Search = CGAL::Orthogonal_k_neighbor_search<CGAL::Search_traits_3<Kernel>>;
  const int D = p.dimension;
  auto point = [&](std::size_t i) {
    return Kernel::Point_3(p.position[i * D], p.position[i * D + 1], D == 3 ? p.position[i * D + 2] : 0.0);
  };
  std::vector<Kernel::Point_3> boundary;
  for (std::size_t i = 0; i < p.owned; ++i)
    if (p.boundary_id[i] > 0) boundary.push_back(point(i));
  if (boundary.empty()) return;
  Search::Tree tree(boundary.begin(), boundary.end());
  tree.build();
  const double depth2 = depth * depth;
  for (std::size_t i = 0; i < p.owned; ++i) {
    const Search nearest(tree, point(i), 1);
    p.no_fail[i] = nearest.begin()->second < depth2 ? 1 : 0;
  }
}

void record_family_volume(PointData& p, const BondFamilies& f) {
  for (std::size_t i = 0; i < p.owned; ++i) {
    double v = 0.0;
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) v += p.volume[static_cast<std::size_t>(f.neighbor[b])];
    p.family_volume[i] = v;
  }
}

std::vector<double> damage_field(const PointData& p, const BondFamilies& f) {
  std::vector<double> d(p.owned, 0.0);
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (!(p.family_volume[i] > 0.0)) continue;
    double acting = 0.0;
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
      if (f.intact[b]) acting += p.volume[static_cast<std::size_t>(f.neighbor[b])];
    d[i] = 1.0 - acting / p.family_volume[i];
  }
  return d;
}

namespace {

// The entry of bond (j, i) in j's list (neighbours are sorted by index).
std::int64_t reverse_bond(const BondFamilies& f, std::size_t i, std::size_t j) {
  const auto* first = f.neighbor.data() + f.offset[j];
  const auto* last = f.neighbor.data() + f.offset[j + 1];
  const auto* it = std::lower_bound(first, last, static_cast<std::int32_t>(i));
  return it != last && *it == static_cast<std::int32_t>(i) ? static_cast<std::int64_t>(it - f.neighbor.data()) : -1;
}

}  // namespace

BreakageUpdate update_after_breakage(PointData& p, BondFamilies& f, const CosseratConstants& c) {
  BreakageUpdate u;
  std::vector<std::size_t> changed;
  std::size_t broken_ends = 0;
  for (std::size_t i = 0; i < p.owned; ++i)
    if (p.bonds_broken[i] > 0) {
      changed.push_back(i);
      broken_ends += static_cast<std::size_t>(p.bonds_broken[i]);
    }
  // A point that a break leaves with a singular shape tensor is detached, and SPEC section 2 has it
  // move ballistically: its remaining bonds break too (their work is dissipated like any other
  // bond's), which can detach a neighbour in turn. Serial and in index order: the same for any
  // thread count. Points detached from the start (isolated by the geometry) are left as they are.
  while (!changed.empty()) {
    std::vector<std::uint8_t> was_detached(changed.size());
    for (std::size_t k = 0; k < changed.size(); ++k) was_detached[k] = p.detached[changed[k]];
    update_shape_tensors(p, f, c, changed);
    std::vector<std::size_t> next;
    for (std::size_t k = 0; k < changed.size(); ++k) {
      const std::size_t i = changed[k];
      if (was_detached[k] || !p.detached[i]) continue;
      ++u.newly_detached;
      for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
        if (!f.intact[b]) continue;
        const auto j = static_cast<std::size_t>(f.neighbor[b]);
        const std::int64_t rb = reverse_bond(f, i, j);
        f.intact[b] = 0;
        if (rb >= 0) f.intact[rb] = 0;
        const double released = 0.5 * p.volume[i] * p.volume[j] * f.work[b];
        p.fracture_dissipation[i] += released;
        p.fracture_dissipation[j] += released;
        broken_ends += 2;
        next.push_back(j);
      }
    }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    changed = std::move(next);
  }
  u.broken_pairs = broken_ends / 2;
  return u;
}

}  // namespace mppm::solver
