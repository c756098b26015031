// Derivation and validation of the Cosserat constants from the scene (SPEC sections 4-5).
#include "solver/cosserat_material.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "common/input_error.hpp"

namespace mppm::solver {

namespace {
[[noreturn]] void refuse(const Scene& scene, const std::string& key, const std::string& problem) {
  throw InputError(scene.path + ": " + key + ": " + problem);
}
std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

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
  c.density = m.solid_fraction * m.density;
  c.solid_fraction = m.solid_fraction;
  c.length_scale = m.length_scale;
  c.micro_inertia = 0.5 * std::numbers::pi * c.density * m.length_scale * m.length_scale;
  c.stabilization = scene.numerics.stabilization;

  const double d = scene.dimension;
  if (!(m.density > 0.0)) refuse(scene, "material.density", "must be positive, got " + num(m.density));
  if (!(m.solid_fraction > 0.0 && m.solid_fraction <= 1.0))
    refuse(scene, "material.solid_fraction", "must be in (0, 1], got " + num(m.solid_fraction));
  if (!(m.mu > 0.0)) refuse(scene, "material.mu", "must be positive, got " + num(m.mu));
  if (!(m.lambda + 2.0 * m.mu / d > 0.0))
    refuse(scene, "material.lambda", "lambda + 2 mu / d must be positive (bulk modulus), got lambda = " +
                                         num(m.lambda));
  if (!(c.stabilization >= 0.0))
    refuse(scene, "numerics.stabilization", "must be >= 0, got " + num(c.stabilization));
  if (c.micropolar) {
    if (!(m.mu_c >= 0.0)) refuse(scene, "material.mu_c", "must be >= 0, got " + num(m.mu_c));
    if (!(m.length_scale > 0.0))
      refuse(scene, "material.length_scale",
             "must be positive with the micropolar effect (it sets the micro-inertia)");
    if (scene.dimension == 2) {
      if (!(c.a3 > 0.0))
        refuse(scene, "material.couple_moduli",
               "a3 (the 2-D bending modulus B_w) must be positive, got " + num(c.a3) + " N");
    } else if (!(c.a2 + c.a3 > 0.0 && c.a2 - c.a3 >= 0.0 && 3.0 * c.a1 + c.a2 + c.a3 >= 0.0)) {
      refuse(scene, "material.couple_moduli",
             "[a1, a2, a3] = [" + num(c.a1) + ", " + num(c.a2) + ", " + num(c.a3) +
                 "] N give a couple-stress energy that is not positive (3-D needs a2 + a3 > 0, "
                 "a2 >= a3, 3 a1 + a2 + a3 >= 0)");
    }
  }
  return c;
}

}  // namespace mppm::solver
