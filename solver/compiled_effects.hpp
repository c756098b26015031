// The effect set as a compile-time type (docs/theory.md section 10): kernels are templated on it so that
// an effect that is off is compiled out (no memory, no loop work), and a runtime EffectSet is
// turned into the matching instantiation exactly once, when the model is built.
#pragma once
#include "common/scene.hpp"

namespace mppm::solver {

template <bool Micropolar, bool Damage, bool Viscoplasticity, bool PoreFluid = false>
struct CompiledEffects {
  static constexpr bool micropolar = Micropolar;
  static constexpr bool damage = Damage;  // bonds can be broken (BondFamilies::acting), kernels honour it
  static constexpr bool viscoplasticity = Viscoplasticity;  // stress from eps - eps_vp
  static constexpr bool pore_fluid = PoreFluid;             // total stress sigma' - b p 1 (docs/theory.md section 12)
};

// Number of micro-rotation components: the scalar w_z in 2-D, a vector in 3-D.
template <int D>
inline constexpr int rotation_components = D == 2 ? 1 : 3;

inline int rotation_components_of(int dimension) { return dimension == 2 ? 1 : 3; }

// Calls f.template operator()<D, CompiledEffects<...>>() for the runtime choice. Gravity is a
// body force applied by the integrator, not a kernel concern, so it is not part of the type.
template <class F>
decltype(auto) dispatch_effects(int dimension, const EffectSet& effects, F&& f) {
  auto by_dimension = [&]<bool M, bool Dm, bool V, bool P>() -> decltype(auto) {
    if (dimension == 2) return f.template operator()<2, CompiledEffects<M, Dm, V, P>>();
    return f.template operator()<3, CompiledEffects<M, Dm, V, P>>();
  };
  auto by_fluid = [&]<bool M, bool Dm, bool V>() -> decltype(auto) {
    if (effects.pore_fluid) return by_dimension.template operator()<M, Dm, V, true>();
    return by_dimension.template operator()<M, Dm, V, false>();
  };
  auto by_plasticity = [&]<bool M, bool Dm>() -> decltype(auto) {
    if (effects.viscoplasticity) return by_fluid.template operator()<M, Dm, true>();
    return by_fluid.template operator()<M, Dm, false>();
  };
  auto by_damage = [&]<bool M>() -> decltype(auto) {
    if (effects.damage) return by_plasticity.template operator()<M, true>();
    return by_plasticity.template operator()<M, false>();
  };
  if (effects.micropolar) return by_damage.template operator()<true>();
  return by_damage.template operator()<false>();
}

}  // namespace mppm::solver
