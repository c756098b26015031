// Run-time selection of viscoplastic models by name (the scene key
// material.viscoplasticity.model), OpenFOAM style: a table name -> factory, and an unknown
// name is refused with the sorted list of valid names, so the message never goes stale.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/scene.hpp"
#include "solver/plasticity/viscoplastic_model.hpp"

namespace mppm::plasticity {

class MaterialRegistry {
 public:
  // A factory reads material.viscoplasticity (and material.length_scale) and may throw
  // std::invalid_argument("KEY: problem"), KEY relative to `material.`.
  using Factory = std::function<std::unique_ptr<ViscoplasticModel>(const Material& material)>;

  // The process-wide table, holding the built-in models. Add to it at start-up only
  // (registration is not synchronized; lookups are read-only and thread-safe).
  static MaterialRegistry& viscoplastic();

  void add(const std::string& name, Factory factory);  // std::logic_error on a duplicate name
  bool contains(const std::string& name) const { return factories_.count(name) != 0; }
  std::vector<std::string> names() const;  // sorted

  // Resolves material.viscoplasticity.model. `source` names the scene file in messages.
  // Throws InputError("SOURCE: material.viscoplasticity.model: unknown model 'x'
  // (valid: a, b)") or InputError("SOURCE: material.KEY: problem") for bad parameters.
  std::unique_ptr<ViscoplasticModel> create(const Material& material, const std::string& source) const;

 private:
  std::map<std::string, Factory> factories_;
};

// MaterialRegistry::viscoplastic().create(material, source).
std::unique_ptr<ViscoplasticModel> make_viscoplastic_model(const Material& material, const std::string& source);

// The model parameters of a scene's material block (angles in radians, SI).
DruckerPragerParameters drucker_prager_parameters(const Material& material);

}  // namespace mppm::plasticity
