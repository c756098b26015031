// Instantiations of the internal-force kernel for every dimension and effect combination (this
// file is compiled with fused multiply-adds: solver/CMakeLists.txt).
#include "solver/internal_forces.hpp"

#include "solver/internal_force_kernel.hpp"

namespace mppm::solver {

InternalForceFunctions internal_force_functions(int dimension, const EffectSet& effects) {
  return dispatch_effects(dimension, effects, [&]<int D, class E>() {
    InternalForceFunctions functions;
    functions.forces = &kernel::internal_forces<D, E, false>;
    functions.forces_and_energy = &kernel::internal_forces<D, E, true>;
    functions.refresh_after_breakage = &kernel::refresh_after_breakage<D, E>;
    add_energy_functions(dimension, effects, functions);  // internal_energies.cpp
    return functions;
  });
}

}  // namespace mppm::solver
