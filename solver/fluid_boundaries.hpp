// The pore fluid's drained boundaries in the model (docs/theory.md section 12): the layer points of a
// drained (pore_pressure) condition carry the prescribed pressure, and the fluid of a body point
// also flows over its bonds to them, the drain bonds. A drained layer that is no kinematic
// condition's (an inert layer) takes no part in the mechanics: its bonds leave the families at
// both ends before anything reads them, so that the mechanics are those of the run without it, and
// the drain bonds to it are kept here. A drained kinematic layer keeps its bonds in the families;
// its drain bonds conduct while those act.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// The layer points of one drained condition (BoundaryConditions::drained(), in that order); inert
// when no kinematic condition has the layer.
struct DrainedPoints {
  std::vector<std::int32_t> points;
  bool inert = false;
};

// What build_model needs to know of the fluid's boundaries (BoundaryConditions::fluid_layout).
struct FluidBoundaryLayout {
  std::vector<DrainedPoints> drained;
  // The boundary ids of points that carry a fluid condition only (inert drained layers, fed points
  // of a flux of their own): they make no no-fail zone (docs/theory.md section 7), which belongs to
  // the mechanical boundaries.
  std::vector<std::int32_t> fluid_only_ids;
};

// One bond from a body point to a drained-layer point.
struct DrainBond {
  std::int32_t body = 0, layer = 0;
  std::int64_t mechanical = -1;             // the bond's entry in the families (a drained kinematic layer), else -1
  std::array<double, 3> xi{0.0, 0.0, 0.0};  // x_layer - x_body (the minimum image on a periodic lattice)
  double length = 0.0;                      // |xi|
  std::int32_t drain = 0;                   // the drained condition (index into FluidBoundaryLayout::drained)
};

// The drain bonds, stored from the body end only, in CSR form over the body points that have any.
struct DrainBonds {
  std::vector<std::int32_t> point;       // body points with drain bonds, increasing
  std::vector<std::int64_t> offset;      // point.size() + 1
  std::vector<std::int32_t> neighbor;    // the drained-layer point of each bond
  std::vector<std::int64_t> mechanical;  // DrainBond::mechanical
  std::vector<double> xi;                // 3 per bond
  std::vector<double> length;
  std::vector<std::int32_t> drain;
  std::size_t drain_count = 0;  // drained conditions
  // Scratch of the flow update: the volume rate each bond carries from its body point into the
  // layer [m^3/s], and per drained condition the volume the last update let out [m^3].
  std::vector<double> pair_flux, outflow;

  bool empty() const { return point.empty(); }
  std::size_t bond_count() const { return neighbor.size(); }
  // Bond b conducts: an inert layer's unless its body point is detached (a detached point keeps its
  // fluid), a kinematic layer's while the bond acts.
  bool conducts(const PointData& p, const BondFamilies& f, std::size_t row, std::size_t b) const {
    return mechanical[b] >= 0 ? f.acting(mechanical[b]) : !p.detached[static_cast<std::size_t>(point[row])];
  }
  // The row of body point i, -1 if it has no drain bond.
  std::ptrdiff_t row_of(std::size_t i) const;
};

// Takes the bonds of the inert layers' points out of the families (from both ends) and returns the
// ones from body points to them, in body point order, as drain bonds.
std::vector<DrainBond> take_out_inert_layers(const PointData& points, BondFamilies& bonds,
                                             const FluidBoundaryLayout& layout);

// The drain bonds: `inert` (take_out_inert_layers, less those a pre-crack cut) and the acting bonds
// of body points to the points of drained kinematic layers, sorted by body point, then layer point.
DrainBonds make_drain_bonds(const PointData& points, const BondFamilies& bonds, const FluidBoundaryLayout& layout,
                            std::vector<DrainBond> inert);

}  // namespace mppm::solver
