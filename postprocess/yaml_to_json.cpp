// YAML -> JSON for the resolved material and boundary-condition blocks.
#include "postprocess/yaml_to_json.hpp"

#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "common/units.hpp"

namespace mppm::post {
namespace {

// Keys whose values are names, never numbers (a boundary may be called "1").
const std::set<std::string>& name_keys() {
  static const std::set<std::string> keys{"name", "boundary", "type", "model", "cone_match"};
  return keys;
}

JsonValue scalar_to_json(const YAML::Node& node, bool is_name) {
  const std::string text = node.Scalar();
  if (is_name || node.Tag() == "!") return JsonValue(text);  // quoted or a name: a string
  if (text == "true" || text == "false") return JsonValue(text == "true");
  if (text == "null" || text == "~") return JsonValue();
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) {
      const bool integral = text.find_first_of(".eE") == std::string::npos && std::fabs(value) < 9e15;
      return integral ? JsonValue(static_cast<std::int64_t>(value)) : JsonValue(value);
    }
  } catch (const std::exception&) {
  }
  try {
    const Quantity q = parse_quantity(text);
    if (q.dimension.is_angle) return JsonValue(q.value * 180.0 / std::numbers::pi);
    return JsonValue(q.value);
  } catch (const std::exception&) {
  }
  return JsonValue(text);
}

JsonValue convert(const YAML::Node& node, bool is_name) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return scalar_to_json(node, is_name);
    case YAML::NodeType::Sequence: {
      auto array = JsonValue::array();
      for (const auto& item : node) array.push(convert(item, is_name));
      return array;
    }
    case YAML::NodeType::Map: {
      auto object = JsonValue::object();
      for (const auto& member : node) {
        const std::string key = member.first.as<std::string>();
        object.set(key, convert(member.second, name_keys().count(key) > 0));
      }
      return object;
    }
    default:
      return JsonValue();
  }
}

}  // namespace

JsonValue yaml_to_json(const YAML::Node& node) { return convert(node, false); }

}  // namespace mppm::post
