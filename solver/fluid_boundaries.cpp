// The drain bonds and the inert drained layers (see fluid_boundaries.hpp; docs/theory.md section 12).
#include "solver/fluid_boundaries.hpp"

#include <algorithm>
#include <cmath>

namespace mppm::solver {

namespace {

// Per point: the drained condition of its layer (-1: none) and whether that layer is inert.
struct DrainMarks {
  std::vector<std::int32_t> drain;
  std::vector<std::uint8_t> inert;
};

DrainMarks mark_drained_points(const PointData& p, const FluidBoundaryLayout& layout) {
  DrainMarks m{std::vector<std::int32_t>(p.total(), -1), std::vector<std::uint8_t>(p.total(), 0)};
  for (std::size_t k = 0; k < layout.drained.size(); ++k)
    for (const std::int32_t i : layout.drained[k].points) {
      m.drain[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(k);
      m.inert[static_cast<std::size_t>(i)] = layout.drained[k].inert ? 1 : 0;
    }
  return m;
}

// The drain bond of bond b of body point i.
DrainBond drain_bond(const BondFamilies& f, const PointData& p, std::size_t i, std::int64_t b, std::int64_t mechanical,
                     std::int32_t drain) {
  DrainBond d;
  d.body = static_cast<std::int32_t>(i);
  d.layer = static_cast<std::int32_t>(f.neighbor_of(b));
  d.mechanical = mechanical;
  bond_vector(f, p, i, b, d.xi.data());
  d.length = std::sqrt(d.xi[0] * d.xi[0] + d.xi[1] * d.xi[1] + d.xi[2] * d.xi[2]);
  d.drain = drain;
  return d;
}

bool is_body(const PointData& p, std::size_t i) { return p.region[i] == 0; }

}  // namespace

std::ptrdiff_t DrainBonds::row_of(std::size_t i) const {
  const auto it = std::lower_bound(point.begin(), point.end(), static_cast<std::int32_t>(i));
  return it != point.end() && *it == static_cast<std::int32_t>(i) ? it - point.begin() : -1;
}

std::vector<DrainBond> take_out_inert_layers(const PointData& p, BondFamilies& f, const FluidBoundaryLayout& layout) {
  const DrainMarks marks = mark_drained_points(p, layout);
  std::vector<DrainBond> drains;
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (!is_body(p, i)) continue;
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const std::size_t j = f.neighbor_of(b);
      if (!marks.inert[j]) continue;
      drains.push_back(drain_bond(f, p, i, b, -1, marks.drain[j]));
    }
  }
  remove_bonds(f, [&](std::size_t i, std::size_t b) {
    return marks.inert[i] != 0 || marks.inert[f.neighbor_of(static_cast<std::int64_t>(b))] != 0;
  });
  return drains;
}

DrainBonds make_drain_bonds(const PointData& p, const BondFamilies& f, const FluidBoundaryLayout& layout,
                            std::vector<DrainBond> bonds) {
  const DrainMarks marks = mark_drained_points(p, layout);
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (!is_body(p, i)) continue;
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const std::size_t j = f.neighbor_of(b);
      if (marks.drain[j] < 0 || marks.inert[j] || !f.acting(b)) continue;
      bonds.push_back(drain_bond(f, p, i, b, b, marks.drain[j]));
    }
  }
  std::sort(bonds.begin(), bonds.end(), [](const DrainBond& a, const DrainBond& b) {
    return a.body != b.body ? a.body < b.body : a.layer < b.layer;
  });
  DrainBonds d;
  d.drain_count = layout.drained.size();
  d.offset.push_back(0);
  for (const DrainBond& bond : bonds) {
    if (d.point.empty() || d.point.back() != bond.body) {
      if (!d.point.empty()) d.offset.push_back(static_cast<std::int64_t>(d.neighbor.size()));
      d.point.push_back(bond.body);
    }
    d.neighbor.push_back(bond.layer);
    d.mechanical.push_back(bond.mechanical);
    d.xi.insert(d.xi.end(), bond.xi.begin(), bond.xi.end());
    d.length.push_back(bond.length);
    d.drain.push_back(bond.drain);
  }
  if (!d.point.empty()) d.offset.push_back(static_cast<std::int64_t>(d.neighbor.size()));
  d.pair_flux.assign(d.neighbor.size(), 0.0);
  d.outflow.assign(d.drain_count, 0.0);
  return d;
}

}  // namespace mppm::solver
