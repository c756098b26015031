// Instantiations of the internal-force kernel for every dimension and effect combination (its
// fused multiply-adds are written in the source: solver/multiply_add.hpp).
#include "solver/internal_forces.hpp"

#include "solver/internal_force_kernel.hpp"

namespace mppm::solver {

namespace {

// The instantiation without damage and viscoplasticity: with every bond acting and a zero plastic
// state, the damage kernel skips nothing and the viscoplastic one subtracts zero, so this kernel is
// the same operator.
InternalForceFunction elastic_force_function(int dimension, EffectSet effects) {
  effects.damage = false;
  effects.viscoplasticity = false;
  return dispatch_effects(dimension, effects, []<int D, class E>() -> InternalForceFunction {
    return &kernel::internal_forces<D, E, false>;
  });
}

}  // namespace

InternalForceFunctions internal_force_functions(int dimension, const EffectSet& effects) {
  return dispatch_effects(dimension, effects, [&]<int D, class E>() {
    InternalForceFunctions functions;
    functions.forces = &kernel::internal_forces<D, E, false>;
    functions.forces_and_energy = &kernel::internal_forces<D, E, true>;
    functions.refresh_after_breakage = &kernel::refresh_after_breakage<D, E>;
    add_energy_functions(dimension, effects, functions);  // internal_energies.cpp
    functions.elastic_forces = elastic_force_function(dimension, effects);
    return functions;
  });
}

}  // namespace mppm::solver
