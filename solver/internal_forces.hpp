// Entry point of the internal-force kernel for a runtime effect set: the instantiation is chosen
// once (compute_internal_forces_function) and then called every step.
#pragma once
#include "common/scene.hpp"
#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/step_advance.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// The last argument advances the history-dependent state by one step: the viscoplastic state,
// and with damage the bond work and breakage (nullptr: frozen, bonds as they are). The bonds are
// written only with damage (the `intact` flags and the work).
using InternalForceFunction = void (*)(PointData&, BondFamilies&, const CosseratConstants&, const StepAdvance*);

struct InternalForceFunctions {
  InternalForceFunction forces = nullptr;              // force and moment only
  InternalForceFunction forces_and_energy = nullptr;   // also the per-point energies
};

InternalForceFunctions internal_force_functions(int dimension, const EffectSet& effects);

}  // namespace mppm::solver
