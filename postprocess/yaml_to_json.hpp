// Blocks of the resolved scene (YAML) as JSON for summary.json: numbers stay SI, quantities
// written with a unit ("35 deg") become numbers (angles in degrees, everything else SI).
#pragma once
#include <yaml-cpp/yaml.h>

#include "postprocess/json_value.hpp"

namespace mppm::post {

JsonValue yaml_to_json(const YAML::Node& node);

}  // namespace mppm::post
