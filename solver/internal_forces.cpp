// Instantiations of the internal-force kernel for every dimension and effect combination.
#include "solver/internal_forces.hpp"

#include "solver/internal_force_kernel.hpp"

namespace mppm::solver {

InternalForceFunctions internal_force_functions(int dimension, const EffectSet& effects) {
  return dispatch_effects(dimension, effects, []<int D, class E>() {
    return InternalForceFunctions{&kernel::internal_forces<D, E, false>, &kernel::internal_forces<D, E, true>,
                                  &kernel::stored_energy_of_point<D, E>, &kernel::elastic_energy_of_point<D, E>,
                                  &kernel::elastic_energy_sums<D, E>, &kernel::refresh_after_breakage<D, E>};
  });
}

}  // namespace mppm::solver
