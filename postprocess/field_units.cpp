// Field name -> SI unit (docs/stages.md field names; couple stress is a moment per area: N m/m^2).
#include "postprocess/field_units.hpp"

#include <map>

namespace mppm::post {

std::string field_unit(const std::string& name) {
  static const std::map<std::string, std::string> units{
      {"displacement", "m"},
      {"rotation", "rad"},
      {"velocity", "m/s"},
      {"angular_velocity", "rad/s"},
      {"rotation_rate", "rad/s"},
      {"detached", "-"},
      {"damage", "-"},
      {"crack_area", "m^2"},
      {"plastic_strain", "-"},
      {"plastic_shear_strain", "-"},
      {"equivalent_plastic_strain", "-"},
      {"volumetric_plastic_strain", "-"},
      {"strain", "-"},
      {"wryness", "1/m"},
      {"stress", "Pa"},
      {"von_mises_stress", "Pa"},
      {"mean_stress", "Pa"},
      {"couple_stress", "N/m"},
      {"couple_stress_magnitude", "N/m"},
      {"porosity", "-"},
      {"pore_pressure", "Pa"},
      {"fluid_content", "-"},
      {"saturation", "-"},
      {"darcy_velocity", "m/s"},
      {"volume", "m^3"},
      {"region", "-"},
      {"boundary_id", "-"},
  };
  const auto it = units.find(name);
  return it == units.end() ? std::string() : it->second;
}

}  // namespace mppm::post
