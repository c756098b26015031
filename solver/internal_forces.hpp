// Entry point of the internal-force kernel for a runtime effect set: the instantiation is chosen
// once (compute_internal_forces_function) and then called every step.
#pragma once
#include "common/scene.hpp"
#include "solver/bond_families.hpp"
#include "solver/cosserat_material.hpp"
#include "solver/plastic_step.hpp"
#include "solver/point_data.hpp"

namespace mppm::solver {

// The last argument advances the viscoplastic state by one step (nullptr: frozen; ignored
// without the viscoplasticity effect).
using InternalForceFunction = void (*)(PointData&, const BondFamilies&, const CosseratConstants&,
                                       const PlasticStep*);

struct InternalForceFunctions {
  InternalForceFunction forces = nullptr;              // force and moment only
  InternalForceFunction forces_and_energy = nullptr;   // also the per-point energies
};

InternalForceFunctions internal_force_functions(int dimension, const EffectSet& effects);

}  // namespace mppm::solver
