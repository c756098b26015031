// Super-time-stepping of the pore fluid's flow (docs/theory.md section 12): when the flow's stability
// limit is far below the mechanical step, one update of the whole step by the second-order
// Runge-Kutta-Legendre method (RKL2: Meyer, Balsara and Aslam, J. Comput. Phys. 257, 2014) of s
// stages replaces ~s^2 / 2 explicit substeps. Each stage is a linear combination of fluid contents and
// rates with coefficients summing to one, so the fluid stays conserved to round-off; the volume through
// the drained boundaries is carried through the stages like the content, so the balance closes.
#pragma once
#include <cstdint>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/point_data.hpp"
#include "solver/pore_fluid.hpp"

namespace mppm::solver {

// The fewest RKL2 stages (at least 2) whose stability interval holds a step `span` with the
// margin 0.9 of the explicit limit fluid_step: span <= 0.9 fluid_step (s^2 + s - 2) / 4.
std::int64_t rkl2_stages(double span, double fluid_step);

// The stage coefficients of an s-stage RKL2 step: stage 1 is Y1 = Y0 + first_rate tau L(Y0); stage
// j >= 2 is Yj = mu Y(j-1) + nu Y(j-2) + (1 - mu - nu) Y0 + rate tau L(Y(j-1)) + start_rate tau L(Y0).
struct Rkl2Stage {
  double mu = 0.0, nu = 0.0, rate = 0.0, start_rate = 0.0;
};
struct Rkl2Coefficients {
  double first_rate = 0.0;
  std::vector<Rkl2Stage> stages;  // j = 2 .. s
};
Rkl2Coefficients rkl2_coefficients(std::int64_t stages);

// The arrays a super step works in (kept from step to step: no allocation after the first).
struct FlowSuperStepWork {
  std::vector<double> start_content, start_rate, increment, previous_increment;  // per point
  std::vector<double> start_outflow, previous_outflow, outflow;                  // per drained condition
};

// One RKL2 step of length span in `stages` stages at the skeleton's last strain, with the boundaries
// of `boundaries` (sources constant over the step). pressure_before holds the pressures it starts
// from. Leaves p and zeta at the step's end, drains->outflow the volume each drained condition let
// out; returns the stored fluid energy the step removed (the flow's dissipation and what the fluid
// carried out: docs/theory.md section 12), summed in point chunks fixed by the point count.
double flow_super_step(PointData& points, const BondFamilies& bonds, const FluidConstants& fluid, double span,
                       std::int64_t stages, FlowBoundaries* boundaries, const std::vector<double>& pressure_before,
                       FlowSuperStepWork& work);

}  // namespace mppm::solver
