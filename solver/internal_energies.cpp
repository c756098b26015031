// Instantiations of the kernel's energy functions for every dimension and effect combination,
// compiled with the project's default -ffp-contract=off (internal_forces.hpp says why).
#include "solver/internal_force_kernel.hpp"
#include "solver/internal_forces.hpp"

namespace mppm::solver {

void add_energy_functions(int dimension, const EffectSet& effects, InternalForceFunctions& functions) {
  dispatch_effects(dimension, effects, [&]<int D, class E>() {
    functions.point_energy = &kernel::stored_energy_of_point<D, E>;
    functions.elastic_energy = &kernel::elastic_energy_of_point<D, E>;
    functions.stored_energy_sums = &kernel::stored_energy_sums<D, E>;
    return 0;
  });
}

}  // namespace mppm::solver
