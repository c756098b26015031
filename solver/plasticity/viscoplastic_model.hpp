// The interface a viscoplastic material model offers the solver: the per-point update in
// 2-D and 3-D and the initial state. Models are created by name (material_registry.hpp).
// A hot kernel may instead call the concrete model's free function directly (no virtual
// call per point); the interface is what the solver needs to stay model-agnostic.
#pragma once
#include <string>

#include "solver/plasticity/drucker_prager_perzyna.hpp"

namespace mppm::plasticity {

class ViscoplasticModel {
 public:
  virtual ~ViscoplasticModel() = default;
  virtual std::string name() const = 0;
  virtual PlasticState<2> initial_state_2d() const = 0;
  virtual PlasticState<3> initial_state_3d() const = 0;
  // The cohesion c(ebar) [Pa] of the state with equivalent plastic strain ebar: the models' cohesion
  // is a function of ebar, so the solver passes it into update() from ebar instead of storing it
  // per point.
  virtual double cohesion_at(double equivalent_plastic_strain) const = 0;
  virtual PointUpdate<2> update(const Eigen::Matrix3d& strain, const Eigen::Vector2d& wryness,
                                const PlasticState<2>& state, const CosseratElasticity<2>& elasticity,
                                double dt) const = 0;
  virtual PointUpdate<3> update(const Eigen::Matrix3d& strain, const Eigen::Matrix3d& wryness,
                                const PlasticState<3>& state, const CosseratElasticity<3>& elasticity,
                                double dt) const = 0;
};

// "drucker-prager-perzyna": docs/theory.md section 6.
class DruckerPragerPerzynaModel final : public ViscoplasticModel {
 public:
  explicit DruckerPragerPerzynaModel(const DruckerPragerPerzyna& model) : model_(model) {}
  static constexpr const char* kName = "drucker-prager-perzyna";
  const DruckerPragerPerzyna& constants() const { return model_; }

  std::string name() const override { return kName; }
  PlasticState<2> initial_state_2d() const override { return initial_plastic_state<2>(model_); }
  PlasticState<3> initial_state_3d() const override { return initial_plastic_state<3>(model_); }
  double cohesion_at(double equivalent_plastic_strain) const override {
    return model_.cohesion_at(equivalent_plastic_strain);
  }
  PointUpdate<2> update(const Eigen::Matrix3d& strain, const Eigen::Vector2d& wryness, const PlasticState<2>& state,
                        const CosseratElasticity<2>& elasticity, double dt) const override {
    return drucker_prager_perzyna_update(strain, wryness, state, elasticity, model_, dt);
  }
  PointUpdate<3> update(const Eigen::Matrix3d& strain, const Eigen::Matrix3d& wryness, const PlasticState<3>& state,
                        const CosseratElasticity<3>& elasticity, double dt) const override {
    return drucker_prager_perzyna_update(strain, wryness, state, elasticity, model_, dt);
  }

 private:
  DruckerPragerPerzyna model_;
};

}  // namespace mppm::plasticity
