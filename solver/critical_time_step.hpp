// The stable time step of the explicit scheme (docs/theory.md section 9): the largest eigenvalue of
// M^-1 K of the actual discrete operator (stabilization included) by a Lanczos (Krylov-refined
// power) iteration, plus the same for the translational block (w = 0) and the rotational block
// (u = 0) to name the mode that limits the step and the parameter that drives it.
#pragma once
#include <string>

#include "common/scene.hpp"
#include "solver/model.hpp"

namespace mppm::solver {

struct CriticalTimeStep {
  double step = 0.0;           // 2 / omega_max of the coupled operator [s]
  double translational = 0.0;  // of the translational block
  double rotational = 0.0;     // of the rotational block (0 = no rotation dofs)
  std::string limiting_mode;   // "translational" or "rotational"
  std::string driver;          // the parameter that drives the limiting mode, with its value
  int iterations = 0;          // operator applications of the coupled estimate
  int naming_iterations = 0;   // operator applications of the naming (0 when not named)
};

// Each of these leaves the model's displacement and rotation as they were.
// The step and the limiting mode, both from the model.
CriticalTimeStep critical_time_step(Model& model);
// The step only (the coupled estimate; translational, rotational, limiting_mode and driver unset).
CriticalTimeStep coupled_critical_time_step(Model& model);
// Names the mode of a coupled estimate from the model's own block estimates: translational,
// rotational, limiting_mode and driver (with rotations about 1.4 times the coupled estimate's cost:
// coarser estimates, critical_time_step.cpp).
void name_limiting_mode(Model& model, CriticalTimeStep& critical);

// time.step: auto -> safety * critical; a given step above the critical one is refused with an
// InputError naming the limiting mode, its critical value and the parameter driving it. With the
// damage effect the bound is `damage_step` (Model::damage_critical_step) where it is lower.
double choose_time_step(const Scene& scene, const CriticalTimeStep& critical, double damage_step = 0.0);

}  // namespace mppm::solver
