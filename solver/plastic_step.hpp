// What a force evaluation needs to advance the viscoplastic state by one time step: the
// material model (from the registry, material.viscoplasticity.model) and the step length.
// A force evaluation without it (nullptr) keeps the plastic state frozen: the stress is then
// the elastic law of (strain - plastic strain), which is what the start-up evaluation and the
// critical-step estimate (an elastic bound) need.
#pragma once
#include "solver/plasticity/viscoplastic_model.hpp"

namespace mppm::solver {

struct PlasticStep {
  const plasticity::ViscoplasticModel* model = nullptr;
  double dt = 0.0;  // [s], > 0
};

}  // namespace mppm::solver
