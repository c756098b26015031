// Entry point of the internal-force kernel for a runtime effect set: the instantiation is chosen
// once (internal_force_functions, when the model is built) and then called every step.
#pragma once
#include <cstddef>
#include <vector>

#include "common/scene.hpp"
#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/point_data.hpp"
#include "solver/step_advance.hpp"
#include "solver/stored_energy.hpp"

namespace mppm::solver {

// The last argument advances the history-dependent state by one step: the viscoplastic state,
// and with damage the bond work, with the bonds that reach the critical work counted in
// points.bonds_broken (nullptr: frozen). The force pass writes no neighbour list: the bonds it
// counts are broken afterwards (update_after_breakage); of the bonds it writes only their work.
using InternalForceFunction = void (*)(PointData&, BondFamilies&, const CosseratConstants&, const StepAdvance*);

// The energy stored at one point with its bonds and state as they are (kernel::stored_energy_of_point).
using PointEnergyFunction = StoredEnergy (*)(const PointData&, const BondFamilies&, const CosseratConstants&,
                                             std::size_t point);
// The elastic energies of one point at the strain and wryness of the last evaluation
// (kernel::elastic_energy_of_point; its stabilization is 0: see PointData::stabilization_energy).
using ElasticEnergyFunction = StoredEnergy (*)(const PointData&, const CosseratConstants&, std::size_t point);
// Their sums over the owned points, and the sum of the stabilization energies of the last
// evaluation with energies: the stored energy of an energy row (kernel::stored_energy_sums).
using StoredEnergySumFunction = StoredEnergy (*)(const PointData&, const CosseratConstants&);

// Damage: the forces (and energies) again after bonds broke, for the points whose families changed
// and their neighbours, listed in points.refreshed_points (kernel::refresh_after_breakage).
using BreakageRefreshFunction = void (*)(PointData&, BondFamilies&, const CosseratConstants&);

struct InternalForceFunctions {
  InternalForceFunction forces = nullptr;                // force and moment only
  InternalForceFunction forces_and_energy = nullptr;     // also the stabilization energies
  PointEnergyFunction point_energy = nullptr;            // one point's stored energy (breakage)
  ElasticEnergyFunction elastic_energy = nullptr;        // one point's elastic energies (breakage)
  StoredEnergySumFunction stored_energy_sums = nullptr;  // the stored energy's totals (energy rows)
  BreakageRefreshFunction refresh_after_breakage = nullptr;
  // The same model's kernel without the history effects (damage, viscoplasticity): the linear
  // operator K v of the start-up estimates, at fewer instructions per bond, while no bond is broken
  // and no plastic strain is held (Model::linear_operator_kernel).
  InternalForceFunction elastic_forces = nullptr;
};

InternalForceFunctions internal_force_functions(int dimension, const EffectSet& effects);
// Fills the energy entries (point_energy, elastic_energy, stored_energy_sums). They live in their
// own file, compiled without the force kernel's fused multiply-adds: an energy is then the same
// bits wherever it is evaluated (a row's sum, a breakage update), and a viscoplastic point that
// stays elastic stores the elastic model's energy to the bit.
void add_energy_functions(int dimension, const EffectSet& effects, InternalForceFunctions& functions);

}  // namespace mppm::solver
