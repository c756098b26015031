// Derivation of the Cosserat constants from the scene (docs/theory.md sections 4-5).
#include "solver/cosserat_material.hpp"

#include <stdexcept>

#include "common/input_error.hpp"
#include "solver/bond_breakage.hpp"

namespace mppm::solver {

CosseratConstants cosserat_constants(const Scene& scene) {
  const Material& m = scene.material;
  CosseratConstants c;
  c.dimension = scene.dimension;
  c.micropolar = scene.effects.micropolar;
  c.lambda = m.lambda;
  c.mu = m.mu;
  c.mu_c = c.micropolar ? m.mu_c : 0.0;
  c.a1 = m.couple_moduli[0];
  c.a2 = m.couple_moduli[1];
  c.a3 = m.couple_moduli[2];
  c.bending_modulus = m.bending_modulus(scene.dimension);
  c.density = m.partial_density();
  c.micro_inertia = m.micro_inertia();
  if (scene.effects.pore_fluid && m.pore_fluid) {
    // The mixture moves as one: rho = phi_s rho_s + n0 rho_f for the inertia (and gravity),
    // docs/theory.md section 12. (Written as the sum so that rho_f = 0 keeps the dry bits.)
    // Unsaturated: at the start's saturation S_r(initial_pressure) (saturated with a hydrostatic start);
    // the mass does not follow the saturation as it changes (docs/theory.md section 12).
    const double fluid = m.porosity() * m.pore_fluid->fluid_density * start_saturation(*m.pore_fluid);
    c.density = m.partial_density() + fluid;
    c.micro_inertia = m.micro_inertia() * (c.density / m.partial_density());
    c.biot_coefficient = m.pore_fluid->biot_coefficient;
    c.biot_modulus = m.pore_fluid->biot_modulus;
    c.retention = retention_curve(*m.pore_fluid);
    c.fluid_storage = FluidStorage{m.porosity(), c.biot_coefficient, c.biot_modulus};
  }
  c.solid_fraction = m.solid_fraction;
  c.length_scale = m.length_scale;
  c.stabilization = scene.numerics.stabilization;
  c.detach_energy_rise = scene.numerics.detach_energy_rise;
  c.overload_factor = scene.numerics.overload_factor;
  c.damaged_frequency_ratio = scene.numerics.damaged_frequency_ratio;
  if (scene.effects.damage && m.damage) {
    c.hold_compressed_bonds = m.damage->compressed_bonds == CompressedBonds::hold;
    try {
      c.critical_bond_work =
          critical_bond_work(*m.damage, scene.dimension, scene.geometry.spacing, scene.geometry.horizon_factor,
                             scene.thickness, scene.numerics.stabilization);
    } catch (const std::invalid_argument& e) {
      throw InputError(scene.where("material.damage.calibration") + ": " + e.what());
    }
  }

  // Every value was validated where the scene was read (common/scene.cpp), the one place
  // that owns the rules and knows the file lines; nothing is re-checked here.
  return c;
}

}  // namespace mppm::solver
