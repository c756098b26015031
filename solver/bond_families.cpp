// Family search: uniform cell grid of the horizon size; two passes (count, fill) over points in
// parallel, each point writing only its own bond range.
#include "solver/bond_families.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "solver/parallel_policy.hpp"

namespace mppm::solver {

namespace {

struct CellGrid {
  int dimension = 2;
  std::array<double, 3> low{0, 0, 0};
  double size = 1.0;
  std::array<std::int64_t, 3> cells{1, 1, 1};
  std::vector<std::int64_t> start;   // cell -> first entry in `points`
  std::vector<std::int32_t> points;  // point indices sorted by cell

  std::array<std::int64_t, 3> cell_of(const double* x) const {
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int a = 0; a < dimension; ++a)
      c[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x[a] - low[a]) / size)), 0, cells[a] - 1);
    return c;
  }
  std::int64_t linear(const std::array<std::int64_t, 3>& c) const { return (c[2] * cells[1] + c[1]) * cells[0] + c[0]; }
};

CellGrid make_grid(const PointData& p, double size) {
  CellGrid g;
  const int D = p.dimension;
  g.dimension = D;
  g.size = size;
  const std::size_t n = p.total();
  std::array<double, 3> high{0, 0, 0};
  for (int a = 0; a < D; ++a) {
    g.low[a] = n ? p.position[a] : 0.0;
    high[a] = g.low[a];
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < D; ++a) {
      g.low[a] = std::min(g.low[a], p.position[i * D + a]);
      high[a] = std::max(high[a], p.position[i * D + a]);
    }
  for (int a = 0; a < D; ++a)
    g.cells[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>((high[a] - g.low[a]) / size) + 1);
  const std::int64_t total = g.cells[0] * g.cells[1] * g.cells[2];
  std::vector<std::int64_t> cell_of_point(n);
  g.start.assign(static_cast<std::size_t>(total) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    cell_of_point[i] = g.linear(g.cell_of(&p.position[i * D]));
    ++g.start[cell_of_point[i] + 1];
  }
  std::partial_sum(g.start.begin(), g.start.end(), g.start.begin());
  g.points.resize(n);
  std::vector<std::int64_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) g.points[fill[cell_of_point[i]]++] = static_cast<std::int32_t>(i);
  return g;
}

// Visits the candidate neighbours of point i (any order); `visit(j, xi)` with xi = x_j - x_i.
template <class Visit>
void for_each_in_horizon(const PointData& p, const CellGrid* grid, const FamilyOptions& o, std::size_t i, double reach2,
                         Visit&& visit) {
  const int D = p.dimension;
  const double* xi_pos = &p.position[i * D];
  double xi[3];
  auto consider = [&](std::size_t j) {
    if (j == i) return;
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) {
      double d = p.position[j * D + a] - xi_pos[a];
      if (o.period[a] > 0.0) d -= o.period[a] * std::nearbyint(d / o.period[a]);
      xi[a] = d;
      r2 += d * d;
    }
    if (r2 <= reach2) visit(j, xi);
  };
  if (!grid) {
    for (std::size_t j = 0; j < p.total(); ++j) consider(j);
    return;
  }
  const auto c = grid->cell_of(xi_pos);
  std::array<std::int64_t, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int a = 0; a < D; ++a) {
    lo[a] = std::max<std::int64_t>(0, c[a] - 1);
    hi[a] = std::min<std::int64_t>(grid->cells[a] - 1, c[a] + 1);
  }
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
        const std::int64_t cell = grid->linear({x, y, z});
        for (std::int64_t k = grid->start[cell]; k < grid->start[cell + 1]; ++k)
          consider(static_cast<std::size_t>(grid->points[k]));
      }
}

}  // namespace

BondFamilies build_families(const PointData& p, const FamilyOptions& o) {
  if (!(o.horizon > 0.0)) throw std::invalid_argument("build_families: horizon must be positive");
  const int D = p.dimension;
  const bool periodic = o.period[0] > 0.0 || o.period[1] > 0.0 || o.period[2] > 0.0;
  for (int a = 0; a < D; ++a)
    if (o.period[a] > 0.0 && o.period[a] <= 2.0 * o.horizon)
      throw std::invalid_argument("build_families: a period must exceed twice the horizon");
  const double reach = o.horizon + 1e-9 * o.spacing;
  const double reach2 = reach * reach;
  CellGrid grid;
  if (!periodic) grid = make_grid(p, reach);
  const CellGrid* g = periodic ? nullptr : &grid;

  BondFamilies f;
  f.dimension = D;
  const std::size_t n = p.owned;
  f.offset.assign(n + 1, 0);
  const auto sn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (thread_point_loop(n * 8))
  for (std::int64_t s = 0; s < sn; ++s) {
    std::int64_t count = 0;
    for_each_in_horizon(p, g, o, static_cast<std::size_t>(s), reach2, [&](std::size_t, const double*) { ++count; });
    f.offset[s + 1] = count;
  }
  std::partial_sum(f.offset.begin(), f.offset.end(), f.offset.begin());
  const auto bonds = static_cast<std::size_t>(f.offset[n]);
  if (bonds > static_cast<std::size_t>(INT32_MAX) * 64) throw std::length_error("build_families: too many bonds");
  f.neighbor.resize(bonds);
  if (periodic) f.xi.resize(bonds * D);
#pragma omp parallel for schedule(static) if (thread_bond_loop(bonds))
  for (std::int64_t s = 0; s < sn; ++s) {
    const auto i = static_cast<std::size_t>(s);
    std::vector<std::pair<std::int32_t, std::array<double, 3>>> found;
    found.reserve(static_cast<std::size_t>(f.offset[i + 1] - f.offset[i]));
    for_each_in_horizon(p, g, o, i, reach2, [&](std::size_t j, const double* xi) {
      found.push_back({static_cast<std::int32_t>(j), {xi[0], xi[1], D == 3 ? xi[2] : 0.0}});
    });
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::int64_t b = f.offset[i];
    for (const auto& [j, xi] : found) {
      f.neighbor[b] = j;
      if (periodic)
        for (int a = 0; a < D; ++a) f.xi[b * D + a] = xi[a];
      ++b;
    }
  }
  return f;
}

void index_bond_pairs(BondFamilies& f) {
  const auto n = static_cast<std::int64_t>(f.offset.size()) - 1;
  f.pair_offset.assign(static_cast<std::size_t>(n) + 1, 0);
  bool asymmetric = false;
#pragma omp parallel for schedule(static) reduction(|| : asymmetric) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t i = 0; i < n; ++i) {
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const auto j = static_cast<std::int64_t>(f.neighbor_of(b));
      if (j >= n || mirror_bond(f, static_cast<std::size_t>(i), static_cast<std::size_t>(j)) < 0) asymmetric = true;
    }
    f.pair_offset[i + 1] = f.offset[i + 1] - first_bond_above(f, static_cast<std::size_t>(i));
  }
  if (asymmetric) throw std::logic_error("index_bond_pairs: a bond is not stored at both of its (owned) ends");
  std::partial_sum(f.pair_offset.begin(), f.pair_offset.end(), f.pair_offset.begin());
  f.work.assign(static_cast<std::size_t>(f.pair_offset[n]), 0.0);
}

double bond_work(const BondFamilies& f, std::size_t i, std::int64_t b) {
  std::size_t low = i;
  std::int64_t entry = b;
  const std::size_t j = f.neighbor_of(b);
  if (j < i) {
    low = j;
    entry = mirror_bond(f, i, j);
  }
  return f.work[static_cast<std::size_t>(f.pair_offset[low] + (entry - first_bond_above(f, low)))];
}

}  // namespace mppm::solver
