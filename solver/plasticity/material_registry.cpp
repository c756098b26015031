// The viscoplastic model table and the built-in registrations.
#include "solver/plasticity/material_registry.hpp"

#include <stdexcept>

#include "common/input_error.hpp"

namespace mppm::plasticity {

DruckerPragerParameters drucker_prager_parameters(const Material& material) {
  if (!material.viscoplasticity) throw std::invalid_argument("viscoplasticity: missing (the effect needs this block)");
  const ViscoplasticParameters& vp = *material.viscoplasticity;
  DruckerPragerParameters p;
  p.friction_angle = vp.friction_angle;
  p.dilatancy_angle = vp.dilatancy_angle;
  p.cohesion = vp.cohesion;
  p.hardening = vp.hardening;
  p.residual_cohesion = vp.residual_cohesion;
  p.viscosity = vp.viscosity;
  p.length_scale = material.length_scale;
  p.cone_match = vp.cone_match;
  return p;
}

MaterialRegistry& MaterialRegistry::viscoplastic() {
  // Built-ins are added here rather than by static self-registration, which a static
  // library would silently drop when no symbol of the model's object file is referenced.
  static MaterialRegistry registry = [] {
    MaterialRegistry r;
    r.add(DruckerPragerPerzynaModel::kName, [](const Material& material) -> std::unique_ptr<ViscoplasticModel> {
      return std::make_unique<DruckerPragerPerzynaModel>(
          make_drucker_prager_perzyna(drucker_prager_parameters(material)));
    });
    return r;
  }();
  return registry;
}

void MaterialRegistry::add(const std::string& name, Factory factory) {
  if (!factories_.emplace(name, std::move(factory)).second) {
    throw std::logic_error("viscoplastic model '" + name + "' registered twice");
  }
}

std::vector<std::string> MaterialRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& entry : factories_) out.push_back(entry.first);
  return out;
}

std::unique_ptr<ViscoplasticModel> MaterialRegistry::create(const Material& material, const std::string& source) const {
  if (!material.viscoplasticity) {
    throw InputError(source + ": material.viscoplasticity: missing (the effect 'viscoplasticity' needs this block)");
  }
  const std::string& name = material.viscoplasticity->model;
  const auto it = factories_.find(name);
  if (it == factories_.end()) {
    std::string valid;
    for (const std::string& n : names()) valid += (valid.empty() ? "" : ", ") + n;
    throw InputError(source + ": material.viscoplasticity.model: unknown model '" + name + "' (valid models: " + valid +
                     ")");
  }
  try {
    return it->second(material);
  } catch (const std::invalid_argument& e) {
    throw InputError(source + ": material." + e.what());
  }
}

std::unique_ptr<ViscoplasticModel> make_viscoplastic_model(const Material& material, const std::string& source) {
  return MaterialRegistry::viscoplastic().create(material, source);
}

}  // namespace mppm::plasticity
