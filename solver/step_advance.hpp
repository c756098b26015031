// What the force evaluation of a time step needs to advance the history-dependent state by one
// step: the viscoplastic model (from the registry, material.viscoplasticity.model; null without
// that effect) and the step length. With the damage effect, the same evaluation also accumulates
// the work of every bond and counts the bonds that reach the critical work; update_after_breakage
// (bond_breakage.hpp), called by Model::advance_internal_forces after the evaluation, breaks them.
// A force evaluation without it (nullptr) keeps that state frozen: the stress is then the elastic
// law of (strain - plastic strain) on the bonds as they are, which is what the start-up
// evaluation and the critical-step estimate (an elastic bound) need.
#pragma once
#include "solver/plasticity/viscoplastic_model.hpp"

namespace mppm::solver {

struct StepAdvance {
  const plasticity::ViscoplasticModel* plastic_model = nullptr;  // viscoplasticity effect only
  double dt = 0.0;                                               // [s], > 0
};

}  // namespace mppm::solver
