// The resolved scene: every default and derived value written out in SI (angles as "X deg"),
// in a form that load_scene reads back to the same Scene (restart and postprocessing use it).
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <numbers>

#include "common/scene.hpp"

namespace mppm {
namespace {

// Shortest decimal text that reads back to the same double (std::to_chars round trip):
// exact for restart, and "0.95" rather than "0.94999999999999996" for people.
std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}
struct Num {
  double v;
};
YAML::Emitter& operator<<(YAML::Emitter& out, Num n) { return out << shortest(n.v); }

void emit_selector_keys(YAML::Emitter& out, const Selector& s) {
  if (!s.physical_group.empty()) {
    out << YAML::Key << "boundary" << YAML::Value << s.physical_group;
  } else if (!s.entities.empty()) {
    out << YAML::Key << "entities" << YAML::Value << YAML::Flow << s.entities;
  } else if (s.box) {
    out << YAML::Key << "box" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const auto& corner : *s.box) {
      out << YAML::BeginSeq << Num{corner[0]} << Num{corner[1]};
      if (std::abs(corner[2]) < 1e299) out << Num{corner[2]};  // a 2-D box spans every z
      out << YAML::EndSeq;
    }
    out << YAML::EndSeq;
  }
}

std::string degrees(double radians) { return shortest(radians * 180.0 / std::numbers::pi) + " deg"; }

void emit_row(YAML::Emitter& out, const std::vector<double>& values, const std::vector<bool>& constrained) {
  if (values.size() == 1 && constrained.size() <= 1) {
    out << Num{values[0]};
    return;
  }
  out << YAML::Flow << YAML::BeginSeq;
  for (std::size_t c = 0; c < values.size(); ++c) {
    if (c < constrained.size() && !constrained[c])
      out << "free";
    else
      out << Num{values[c]};
  }
  out << YAML::EndSeq;
}

void emit_geometry(YAML::Emitter& out, const Scene& scene) {
  out << YAML::Key << "geometry" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "file" << YAML::Value << scene.geometry.file;
  // The unit is written as a factor name when it is one of the common ones.
  const double u = scene.geometry.unit;
  const char* unit = u == 1.0      ? "m"
                     : u == 1e-3   ? "mm"
                     : u == 1e-2   ? "cm"
                     : u == 1e-6   ? "um"
                     : u == 0.0254 ? "in"
                     : u == 0.3048 ? "ft"
                                   : "m";
  out << YAML::Key << "unit" << YAML::Value << unit;
  out << YAML::Key << "spacing" << YAML::Value << Num{scene.geometry.spacing};
  out << YAML::Key << "horizon_factor" << YAML::Value << Num{scene.geometry.horizon_factor};
  out << YAML::Key << "precracks" << YAML::Value << YAML::BeginSeq;
  for (const auto& s : scene.geometry.precracks) {
    if (!s.physical_group.empty()) {
      out << s.physical_group;
    } else {
      out << YAML::Flow << YAML::BeginMap;
      emit_selector_keys(out, s);
      out << YAML::EndMap;
    }
  }
  out << YAML::EndSeq << YAML::EndMap;
}

// The block an effect is limited to (`region:`), with the keys of its selector.
void emit_region(YAML::Emitter& out, const Selector& region) {
  out << YAML::Key << "region" << YAML::Value << YAML::BeginMap;
  emit_selector_keys(out, region);
  out << YAML::EndMap;
}

void emit_damage(YAML::Emitter& out, const DamageParameters& damage) {
  out << YAML::Key << "damage" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "critical_energy_release_rate" << YAML::Value << Num{damage.critical_energy_release_rate};
  out << YAML::Key << "no_fail_depth" << YAML::Value << Num{damage.no_fail_depth};
  out << YAML::Key << "calibration" << YAML::Value << to_string(damage.calibration);
  out << YAML::Key << "compressed_bonds" << YAML::Value << to_string(damage.compressed_bonds);
  if (damage.region) emit_region(out, *damage.region);
  out << YAML::EndMap;
}

void emit_viscoplasticity(YAML::Emitter& out, const ViscoplasticParameters& vp) {
  out << YAML::Key << "viscoplasticity" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << vp.model;
  out << YAML::Key << "friction_angle" << YAML::Value << degrees(vp.friction_angle);
  out << YAML::Key << "dilatancy_angle" << YAML::Value << degrees(vp.dilatancy_angle);
  out << YAML::Key << "cohesion" << YAML::Value << Num{vp.cohesion};
  out << YAML::Key << "hardening" << YAML::Value << Num{vp.hardening};
  out << YAML::Key << "viscosity" << YAML::Value << Num{vp.viscosity};
  out << YAML::Key << "residual_cohesion" << YAML::Value << Num{vp.residual_cohesion};
  out << YAML::Key << "cone_match" << YAML::Value << to_string(vp.cone_match);
  if (vp.region) emit_region(out, *vp.region);
  out << YAML::EndMap;
}

void emit_pore_fluid(YAML::Emitter& out, const PoreFluidParameters& fluid) {
  out << YAML::Key << "pore_fluid" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "permeability" << YAML::Value << Num{fluid.permeability};
  out << YAML::Key << "fluid_viscosity" << YAML::Value << Num{fluid.fluid_viscosity};
  out << YAML::Key << "fluid_density" << YAML::Value << Num{fluid.fluid_density};
  out << YAML::Key << "biot_coefficient" << YAML::Value << Num{fluid.biot_coefficient};
  out << YAML::Key << "biot_modulus" << YAML::Value << Num{fluid.biot_modulus};
  if (fluid.free_surface) {
    out << YAML::Key << "initial_pressure" << YAML::Value << "hydrostatic";
    out << YAML::Key << "free_surface" << YAML::Value << Num{*fluid.free_surface};
  } else {
    out << YAML::Key << "initial_pressure" << YAML::Value << Num{fluid.initial_pressure};
  }
  if (fluid.retention) {
    const auto& r = *fluid.retention;
    out << YAML::Key << "retention" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "model" << YAML::Value << r.model;
    out << YAML::Key << "air_entry_pressure" << YAML::Value << Num{r.air_entry_pressure};
    out << YAML::Key << "n" << YAML::Value << Num{r.n};
    out << YAML::Key << "residual_saturation" << YAML::Value << Num{r.residual_saturation};
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void emit_material(YAML::Emitter& out, const Scene& scene) {
  const auto& m = scene.material;
  out << YAML::Key << "material" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << m.model;
  out << YAML::Key << "density" << YAML::Value << Num{m.density};
  out << YAML::Key << "solid_fraction" << YAML::Value << Num{m.solid_fraction};
  out << YAML::Key << "lambda" << YAML::Value << Num{m.lambda};
  out << YAML::Key << "mu" << YAML::Value << Num{m.mu};
  if (scene.effects.micropolar) {
    out << YAML::Key << "mu_c" << YAML::Value << Num{m.mu_c};
    out << YAML::Key << "couple_moduli" << YAML::Value << YAML::Flow << YAML::BeginSeq << Num{m.couple_moduli[0]}
        << Num{m.couple_moduli[1]} << Num{m.couple_moduli[2]} << YAML::EndSeq;
    out << YAML::Key << "length_scale" << YAML::Value << Num{m.length_scale};
  }
  if (m.damage) emit_damage(out, *m.damage);
  if (m.viscoplasticity) emit_viscoplasticity(out, *m.viscoplasticity);
  if (m.pore_fluid) emit_pore_fluid(out, *m.pore_fluid);
  out << YAML::EndMap;
}

void emit_effects(YAML::Emitter& out, const Scene& scene) {
  out << YAML::Key << "effects" << YAML::Value << YAML::Flow << scene.effects.names();
  if (scene.effects.gravity) {
    out << YAML::Key << "gravity" << YAML::Value << YAML::Flow << YAML::BeginSeq << Num{scene.gravity[0]}
        << Num{scene.gravity[1]};
    if (scene.dimension == 3) out << Num{scene.gravity[2]};
    out << YAML::EndSeq;
  }
}

void emit_boundary_condition(YAML::Emitter& out, const BoundaryCondition& bc) {
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << bc.name;
  emit_selector_keys(out, bc.selector);
  out << YAML::Key << "type" << YAML::Value << to_string(bc.type);
  if (bc.value.times.size() == 1 && bc.value.times[0] == 0.0) {
    out << YAML::Key << "value" << YAML::Value;
    emit_row(out, bc.value.values[0], bc.constrained);
  } else {
    out << YAML::Key << "history" << YAML::Value << YAML::BeginSeq;
    for (std::size_t r = 0; r < bc.value.times.size(); ++r) {
      out << YAML::Flow << YAML::BeginSeq << Num{bc.value.times[r]};
      emit_row(out, bc.value.values[r], bc.constrained);
      out << YAML::EndSeq;
    }
    out << YAML::EndSeq;
  }
  if (bc.rotation) {
    out << YAML::Key << "rotation_history" << YAML::Value << YAML::BeginSeq;
    for (std::size_t r = 0; r < bc.rotation->times.size(); ++r) {
      out << YAML::Flow << YAML::BeginSeq << Num{bc.rotation->times[r]};
      emit_row(out, bc.rotation->values[r], {});
      out << YAML::EndSeq;
    }
    out << YAML::EndSeq;
  }
  if (has_loaded_depth(bc.type)) out << YAML::Key << "depth" << YAML::Value << Num{bc.traction_depth};
  out << YAML::EndMap;
}

void emit_boundary_conditions(YAML::Emitter& out, const Scene& scene) {
  out << YAML::Key << "boundary_conditions" << YAML::Value << YAML::BeginSeq;
  for (const auto& bc : scene.boundary_conditions) emit_boundary_condition(out, bc);
  out << YAML::EndSeq;
}

void emit_time(YAML::Emitter& out, const Scene& scene) {
  out << YAML::Key << "time" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "end" << YAML::Value << Num{scene.time.end};
  if (scene.time.step) {
    out << YAML::Key << "step" << YAML::Value << Num{*scene.time.step};
  } else {
    out << YAML::Key << "step" << YAML::Value << "auto";
    out << YAML::Key << "safety" << YAML::Value << Num{scene.time.safety};
  }
  out << YAML::EndMap;
}

void emit_output(YAML::Emitter& out, const Scene& scene) {
  out << YAML::Key << "output" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "interval" << YAML::Value << Num{scene.output.interval};
  out << YAML::Key << "load_interval" << YAML::Value << Num{scene.output.load_interval};
  out << YAML::Key << "fields" << YAML::Value << YAML::Flow << scene.output.fields;
  out << YAML::Key << "checkpoint_interval" << YAML::Value << Num{scene.output.checkpoint_interval};
  out << YAML::EndMap;
}

void emit_numerics(YAML::Emitter& out, const Scene& scene) {
  out << YAML::Key << "numerics" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "stabilization" << YAML::Value << Num{scene.numerics.stabilization};
  out << YAML::Key << "damping" << YAML::Value << Num{scene.numerics.damping};
  out << YAML::Key << "energy_check_tolerance" << YAML::Value << Num{scene.numerics.energy_check_tolerance};
  out << YAML::Key << "energy_check_start_step" << YAML::Value << scene.numerics.energy_check_start_step;
  out << YAML::Key << "detach_energy_rise" << YAML::Value << Num{scene.numerics.detach_energy_rise};
  out << YAML::Key << "overload_factor" << YAML::Value << Num{scene.numerics.overload_factor};
  out << YAML::Key << "damaged_frequency_ratio" << YAML::Value << Num{scene.numerics.damaged_frequency_ratio};
  out << YAML::Key << "flow_integration" << YAML::Value << to_string(scene.numerics.flow_integration);
  out << YAML::Key << "step_estimate" << YAML::Value << to_string(scene.numerics.step_estimate);
  out << YAML::EndMap;
}

void emit_derived(YAML::Emitter& out, const Scene& scene, const std::vector<std::pair<std::string, double>>& derived) {
  const auto& m = scene.material;
  out << YAML::Key << "derived" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "horizon_m" << YAML::Value << Num{scene.geometry.horizon()};
  out << YAML::Key << "partial_density_kg_per_m3" << YAML::Value << Num{m.partial_density()};
  if (scene.effects.micropolar) {
    out << YAML::Key << "micro_inertia_kg_per_m" << YAML::Value << Num{m.micro_inertia()};
    out << YAML::Key << "bending_modulus_N" << YAML::Value << Num{m.bending_modulus(scene.dimension)};
  }
  if (m.pore_fluid) {
    out << YAML::Key << "porosity" << YAML::Value << Num{m.porosity()};
    out << YAML::Key << "fluid_mobility_m2_per_Pa_s" << YAML::Value << Num{m.pore_fluid->mobility()};
  }
  for (const auto& [key, value] : derived) out << YAML::Key << key << YAML::Value << Num{value};
  out << YAML::EndMap;
}

}  // namespace

std::string resolved_scene_yaml(const Scene& scene, const std::vector<std::pair<std::string, double>>& derived) {
  YAML::Emitter out;
  out << YAML::Comment("Resolved scene written by mppm " MPPM_VERSION ": SI units, every default filled in.");
  out << YAML::BeginMap;
  out << YAML::Key << "mppm" << YAML::Value << scene.format_version;
  out << YAML::Key << "name" << YAML::Value << scene.name;
  out << YAML::Key << "dimension" << YAML::Value << scene.dimension;
  if (scene.dimension == 2) out << YAML::Key << "thickness" << YAML::Value << Num{scene.thickness};
  emit_geometry(out, scene);
  emit_material(out, scene);
  emit_effects(out, scene);
  emit_boundary_conditions(out, scene);
  emit_time(out, scene);
  emit_output(out, scene);
  emit_numerics(out, scene);
  emit_derived(out, scene, derived);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace mppm
