// The pore fluid's flow on the lattice (docs/theory.md section 12): saturated Darcy flow in bond form,
// Biot storage, the flow step and its stability limit, and the fluid's energy and mass sums.
// The coupling to the skeleton (p from the fluid content and the volumetric strain, the total
// stress sigma' - b p 1) is in pass 1 of the force kernel (internal_force_kernel.hpp); this file
// moves fluid between points at a fixed skeleton.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/scene.hpp"
#include "solver/bond_families.hpp"
#include "solver/fluid_boundaries.hpp"
#include "solver/point_data.hpp"
#include "solver/retention_curve.hpp"

namespace mppm::solver {

struct FluidConstants {
  double biot_coefficient = 1.0;                 // b
  double biot_modulus = 0.0;                     // M [Pa]
  double porosity = 0.0;                         // n0
  double fluid_density = 0.0;                    // rho_f [kg/m^3]
  double mobility = 0.0;                         // k' = k / mu_f [m^2 / (Pa s)]
  double micro_conductivity = 0.0;               // kappa0 of the bond flux [1 / (Pa s m^2)]
  std::array<double, 3> gravity{0.0, 0.0, 0.0};  // g when the gravity effect is on, else zero
  // Unsaturated when set (material.pore_fluid.retention): p from zeta by the retention inverse, the
  // bond conductivity kappa0 (k_r,i + k_r,j) / 2, the capacity d zeta / dp in the flow's limit.
  std::optional<RetentionCurve> retention;
  FluidStorage storage() const { return {porosity, biot_coefficient, biot_modulus}; }
};

// kappa0 = 2 d k' / sum_j |xi_j| V_j over a full interior family of the cubic lattice of spacing
// dx (V_j = dx^3, or dx^2 t in 2-D), with the family builder's inclusion rule (|xi| <= delta + 1e-9 dx):
// the bond flux is then Darcy's flux exactly for a linear pressure, and k' lap p for a quadratic one.
double lattice_micro_conductivity(int dimension, double spacing, double horizon, double thickness, double mobility);

// The constants of a scene with the pore_fluid effect (validated by the scene reader).
FluidConstants fluid_constants(const Scene& scene);

// Sets every body point's fluid content to the initial pressure's at zero strain,
// zeta - n0 = p0 / M, and its pressure to p0 (fictitious layer points: none, p = 0): the constant
// initial_pressure, or with a free surface the hydrostatic p0 = rho_f |g| (free_surface - up . x),
// up = -g / |g|, at which the potential p - rho_f g . x is the same everywhere (no flow).
void start_fluid(PointData& points, const FluidConstants& fluid, double initial_pressure,
                 std::optional<double> free_surface = std::nullopt);

// The fluid-content rate of every body point from the pressures of the last force evaluation,
// Phi_i = sum_j kappa0 (psi_j - psi_i) / |xi| V_j over the acting bonds to body points, with the
// potential psi = p - rho_f g . x; into points.fluid_rate. Fictitious layers are impermeable
// here: the drained ones conduct through their drain bonds (flow_update).
void fluid_rates(PointData& points, const BondFamilies& bonds, const FluidConstants& fluid);

// A fluid-flux boundary's source on its points: s = q A / sum V [1/s] (docs/theory.md section 12).
struct FluidSource {
  const std::vector<std::int32_t>* points = nullptr;
  double rate = 0.0;
};
// The boundaries of a flow update: the drain bonds (their layer points carry the prescribed
// pressure already: BoundaryConditions::prescribe_pore_pressure) and the sources.
struct FlowBoundaries {
  DrainBonds* drains = nullptr;
  std::vector<FluidSource> sources;
};

// The rates of a flow update into points.fluid_rate: fluid_rates, then the drain bonds' share of
// Phi (each bond's volume rate into its layer into drains->pair_flux) and the sources of `boundaries`.
void flow_rates(PointData& points, const BondFamilies& bonds, const FluidConstants& fluid, FlowBoundaries* boundaries);

// Per drained condition the volume rate its bonds let out at the last flow_rates [m^3/s], summed in
// bond order, into `rates` (resized to the drained conditions).
void drained_outflow_rates(const DrainBonds& drains, std::vector<double>& rates);

// p = M (zeta - n0 - b tr eps) of every body point at its fluid content and last strain.
void update_pressures(PointData& points, const FluidConstants& fluid);

// The stored fluid energy sum V (p_before^2 - p^2) / (2M) over the attached body points (a detached
// point keeps its fluid but stores no energy), summed in point chunks fixed by the point count.
// Unsaturated, the trapezoid sum -V (p_before + p) / 2 content_increment, booked into
// points.fluid_energy as well (solver/unsaturated_coupling.hpp); content_increment is unused when saturated.
double stored_energy_released(PointData& points, const FluidConstants& fluid,
                              const std::vector<double>& pressure_before, const std::vector<double>& content_increment);

// One flow update of length dt at the skeleton's last strain: zeta += dt (Phi + s) (fluid_rates
// first, then the drain bonds' share of Phi and the sources of `boundaries`), then
// p = M (zeta - n0 - b tr eps) (a detached point's strain is zero). With drain bonds, drains->outflow gets the volume
// each drained condition let out. Returns the stored fluid energy it removed (the flow's dissipation, and the energy
// the fluid carried out through the boundaries: docs/theory.md section 12), summed in point chunks fixed by the point
// count.
double flow_update(PointData& points, const BondFamilies& bonds, const FluidConstants& fluid, double dt,
                   FlowBoundaries* boundaries = nullptr);

// The largest stable flow step, 1 / max_i (M sum_j kappa0 V_j / |xi|) over the body points'
// conducting bonds and drain bonds (infinite when no bond conducts); unsaturated
// 1 / max_i (sum_j kappa_ij V_j / |xi| / (d zeta/dp)_i) at the present pressures.
double fluid_step_limit(const PointData& points, const BondFamilies& bonds, const FluidConstants& fluid,
                        const DrainBonds* drains = nullptr);

// sum_i V_i zeta_i over the body points, as n0 sum_i V_i + sum_i V_i (zeta_i - n0): the fluid volume
// (mass / rho_f) in the pores.
double fluid_volume(const PointData& points, const FluidConstants& fluid);

// How the flow is scheduled against the mechanical step dt: every `interval` steps one update of
// `interval` dt (the fluid step is the larger); else each step either `substeps` updates of
// dt / substeps, or one RKL2 super step of `stages` stages (solver/flow_super_step.hpp).
struct FlowSchedule {
  std::int64_t interval = 1;
  std::int64_t substeps = 1;
  std::int64_t stages = 1;  // > 1: the RKL2 super step
  double fluid_step = 0.0;  // the stability limit it was chosen from [s]
  FlowIntegration integration = FlowIntegration::automatic;
  // Unsaturated: chosen again before every update from the limit at the state then (the capacity and
  // k_r follow the saturation), with an update every step.
  bool follows_saturation = false;
  // The flow-rate evaluations per mechanical step (its cost in bond loops): 1 / interval, the
  // substeps or the stages; one more for the limit when it follows the saturation.
  double rate_evaluations_per_step() const {
    const double rates =
        stages > 1 ? static_cast<double>(stages) : static_cast<double>(substeps) / static_cast<double>(interval);
    return follows_saturation ? rates + 1.0 : rates;
  }
};
// With the margin 0.9: interval = min(floor(0.9 dt_f / dt), kLongestFlowInterval) when dt_f >= dt; else the cheaper of
// ceil(dt / (0.9 dt_f)) substeps and the RKL2 super step of rkl2_stages(dt, dt_f) stages (the
// substeps when they cost no more, or always with FlowIntegration::explicit_substeps).
FlowSchedule flow_schedule(double fluid_step, double dt, FlowIntegration integration = FlowIntegration::automatic);
// The schedule of unsaturated flow: flow_schedule's substeps or super step, an update every step, and
// follows_saturation set (the run chooses it again before each update).
FlowSchedule unsaturated_flow_schedule(double fluid_step, double dt, FlowIntegration integration);
// The longest interval between flow updates when the flow's limit allows longer ones: Mandel's
// specimen carried a ripple of +-1 % of p0 at an update every 9 steps, 0.05 % at 4 (docs/theory.md
// section 12).
inline constexpr std::int64_t kLongestFlowInterval = 4;

// The Darcy velocity of body point i, q = -k' k_r (grad p - rho_f g) (k_r = 1 saturated), with the nonlocal gradient
// grad p = K_i^-1 sum_j V_j (p_j - p_i) xi over its acting bonds to body points and its conducting
// drain bonds (zero for a detached point); D components into q.
void darcy_velocity(const PointData& points, const BondFamilies& bonds, const FluidConstants& fluid, std::size_t i,
                    double* q, const DrainBonds* drains = nullptr);

}  // namespace mppm::solver
