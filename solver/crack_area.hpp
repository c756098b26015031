// The crack surface area that the broken bonds span (docs/theory.md section 7, "Crack area"): the
// `crack_area` snapshot field of 3-D damage runs, from which the postprocessor measures the crack
// area, its start and its front (postprocess/crack_area_metrics.hpp). Point i holds its share,
//   A_i = V_i sum_{j broken} V_j / sum_{j in family} V_j |xi_ij . n_i|,
// with n_i the direction of sum_{j broken} V_j xi_ij (the side its crack lies on) and the family
// as it was before any bond broke or was cut; summed over the points it is the area of a planar
// cut within about 1 % on the lattices of the tests (tests/unit/test_solver_crack_area.cpp).
// The pre-crack's cut bonds are not in the lists any more (they are removed before the first
// step, model.cpp), so the model keeps them aside (PrecrackCutBonds) and A_i counts them as broken.
// A function of the bond state only: the same bits for any thread count and after a restart.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// The bonds the pre-crack cuts removed from both ends: the points that lost bonds (sorted) and
// the neighbours point points[k] lost, neighbor[offset[k]] .. neighbor[offset[k + 1] - 1], in list
// order, with their bond vectors when the lattice is periodic (as BondFamilies::xi). Kept only
// where the crack area is written (damage runs in 3-D); empty otherwise.
struct PrecrackCutBonds {
  std::vector<std::size_t> points;
  std::vector<std::int64_t> offset;
  std::vector<std::int32_t> neighbor;
  std::vector<double> xi;  // D per cut bond, periodic lattices only (else empty)
  bool empty() const { return points.empty(); }
};

// The cut bonds of `families` (the entries a pre-crack cuts, marked broken before the first step),
// before they are removed; their neighbours are stored without the mark.
PrecrackCutBonds record_cut_bonds(const BondFamilies& families);

// A_i [m^2] (m^3 / m in 2-D: the volumes carry the thickness), 0 for a point without broken or cut
// bonds.
double point_crack_area(const PointData& points, const BondFamilies& families, const PrecrackCutBonds& cuts,
                        std::size_t i);

// A point's broken bonds count as pointing one way when |sum V_j xi_j| >= this share of
// sum V_j |xi_j| (0.6 to 0.9 next to a planar crack, 0 for a detached point in the bulk, whose
// bonds point every way); below it their crossing density is the mean over all directions
// (docs/theory.md section 7).
inline constexpr double kCrackAreaDirectedShare = 0.25;

}  // namespace mppm::solver
