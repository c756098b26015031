// Scene reading: YAML -> overrides -> defaults -> validation -> resolved Scene (SI units).
// Every problem is reported as "FILE:LINE: key.path: what is wrong (what was expected)".
#include "common/scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/scene_keys.hpp"
#include "common/units.hpp"

namespace mppm {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kEffectNames{"micropolar", "viscoplasticity", "damage", "gravity", "pore_fluid"};

// Fields a snapshot can hold, and the effect each one needs (empty: always available).
const std::vector<std::pair<std::string, std::string>> kOutputFields{{"displacement", ""},
                                                                     {"velocity", ""},
                                                                     {"rotation", "micropolar"},
                                                                     {"rotation_rate", "micropolar"},
                                                                     {"strain", ""},
                                                                     {"stress", ""},
                                                                     {"wryness", "micropolar"},
                                                                     {"couple_stress", "micropolar"},
                                                                     {"porosity", ""},
                                                                     {"damage", "damage"},
                                                                     {"crack_area", "damage"},
                                                                     {"plastic_strain", "viscoplasticity"},
                                                                     {"plastic_shear_strain", "viscoplasticity"},
                                                                     {"equivalent_plastic_strain", "viscoplasticity"},
                                                                     {"detached", ""},
                                                                     {"pore_pressure", "pore_fluid"},
                                                                     {"fluid_content", "pore_fluid"},
                                                                     {"saturation", "pore_fluid"},
                                                                     {"darcy_velocity", "pore_fluid"}};

// The keys each block of a scene accepts, by the path of the block ("" = top level, "[]" = every
// entry of a list). check_keys reads them from here, so this is the one list of valid keys;
// scene_key_paths() exports it (docs/scene.md documents every one).
const std::vector<std::string> kSelectorKeys{"boundary", "entities", "box"};
const std::vector<std::string> kRegionKeys{"box"};
const std::vector<std::pair<std::string, std::vector<std::string>>> kBlockKeys{
    {"",
     {"mppm", "name", "dimension", "thickness", "geometry", "material", "effects", "gravity", "boundary_conditions",
      "time", "output", "numerics", "derived", "mppm_version"}},
    {"geometry", {"file", "unit", "spacing", "horizon_factor", "precracks"}},
    {"geometry.precracks[]", kSelectorKeys},
    {"material",
     {"model", "density", "solid_fraction", "lambda", "mu", "mu_c", "couple_moduli", "length_scale", "damage",
      "viscoplasticity", "pore_fluid"}},
    {"material.damage", {"critical_energy_release_rate", "no_fail_depth", "calibration", "compressed_bonds", "region"}},
    {"material.damage.region", kRegionKeys},
    {"material.viscoplasticity",
     {"model", "friction_angle", "dilatancy_angle", "cohesion", "hardening", "viscosity", "residual_cohesion",
      "cone_match", "region"}},
    {"material.viscoplasticity.region", kRegionKeys},
    {"material.pore_fluid",
     {"permeability", "fluid_viscosity", "fluid_density", "biot_coefficient", "biot_modulus", "initial_pressure",
      "free_surface", "retention"}},
    {"material.pore_fluid.retention", {"model", "air_entry_pressure", "n", "residual_saturation"}},
    {"boundary_conditions[]",
     {"name", "boundary", "entities", "box", "type", "value", "ramp", "history", "rotation", "rotation_rate",
      "rotation_history", "depth"}},
    {"time", {"end", "step", "safety"}},
    {"output", {"interval", "load_interval", "fields", "checkpoint_interval"}},
    {"numerics",
     {"stabilization", "damping", "energy_check_tolerance", "energy_check_start_step", "detach_energy_rise",
      "overload_factor", "damaged_frequency_ratio", "flow_integration", "step_estimate"}},
};

// "boundary_conditions[2]" -> "boundary_conditions[]"
std::string block_pattern(const std::string& path) {
  std::string out;
  for (std::size_t k = 0; k < path.size(); ++k) {
    out += path[k];
    if (path[k] == '[') {
      while (k + 1 < path.size() && path[k + 1] != ']') ++k;
    }
  }
  return out;
}

const std::vector<std::string>& keys_of_block(const std::string& path) {
  const auto pattern = block_pattern(path);
  for (const auto& [block, keys] : kBlockKeys) {
    if (block == pattern) return keys;
  }
  throw std::logic_error("scene reader: no key table for the block '" + pattern + "'");
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string join(const std::vector<std::string>& items, const std::string& sep = ", ") {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? sep : "") + items[i];
  return out;
}

// "a, b or c"
std::string alternatives(const std::vector<std::string>& items) {
  if (items.size() < 2) return join(items);
  return join(std::vector<std::string>(items.begin(), items.end() - 1)) + " or " + items.back();
}

template <class E, std::size_t N>
std::vector<std::string> enum_names(const std::array<EnumName<E>, N>& table) {
  std::vector<std::string> names;
  for (const auto& entry : table) names.push_back(entry.name);
  return names;
}

// Nearest known name, if close enough to be a likely typo.
std::string suggestion(const std::string& name, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_distance = 3;
  for (const auto& k : known) {
    const auto d = edit_distance(name, k);
    if (d < best_distance) {
      best_distance = d;
      best = k;
    }
  }
  return best.empty() ? "" : "; did you mean '" + best + "'?";
}

// The shortest text that reads back to the same double: "0.35", not "0.34999999999999998", so a
// message shows a value as the user wrote it, still exactly.
std::string format_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

class SceneReader {
 public:
  SceneReader(std::string display_path, std::string scene_dir)
      : file_(std::move(display_path)), dir_(std::move(scene_dir)) {}

  Scene read(const std::string& text, const std::vector<std::string>& overrides) {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw InputError(file_ + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
    }
    if (!root.IsDefined() || root.IsNull())
      throw InputError(file_ +
                       ": the scene is empty (expected a YAML map with keys mppm, dimension, geometry, material, ...)");
    if (!root.IsMap())
      throw InputError(file_ + ":" + std::to_string(root.Mark().line + 1) +
                       ": the scene must be a YAML map of keys (mppm, dimension, geometry, ...)");
    for (const auto& o : overrides) apply_override(root, o);

    scene_.path = file_;
    check_keys(root, "");
    read_header(root);
    read_effects(root);
    read_geometry(require(root, "", "geometry"));
    read_material(require(root, "", "material"));
    read_gravity(root);
    read_boundary_conditions(root);
    read_time(require(root, "", "time"));
    read_output(root["output"]);
    read_numerics(root["numerics"]);
    scene_.key_lines = key_lines_;
    return scene_;
  }

 private:
  std::string file_, dir_;
  std::map<std::string, std::string> overridden_;  // canonical path -> "--set ..." text
  std::map<std::string, int> key_lines_;
  Scene scene_;

  // ---------------------------------------------------------------- locations and errors
  std::string override_for(const std::string& path) const {
    for (const auto& [p, text] : overridden_) {
      if (path == p || path.rfind(p + ".", 0) == 0 || path.rfind(p + "[", 0) == 0) return text;
    }
    return {};
  }
  std::string location(const YAML::Node& node, const std::string& path) const {
    if (auto o = override_for(path); !o.empty()) return file_ + ": " + o;
    if (node.IsDefined() && node.Mark().line >= 0) return file_ + ":" + std::to_string(node.Mark().line + 1);
    return file_;
  }
  [[noreturn]] void fail(const YAML::Node& node, const std::string& path, const std::string& what) const {
    throw InputError(location(node, path) + ": " + (path.empty() ? "(top level)" : path) + ": " + what);
  }
  static std::string child_path(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
  }
  void note_line(const YAML::Node& node, const std::string& path) {
    if (node.IsDefined() && node.Mark().line >= 0) key_lines_[path] = node.Mark().line + 1;
  }

  // ---------------------------------------------------------------- --set
  static std::vector<std::string> split_path(const std::string& path) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : path) {
      if (c == '.' || c == '[' || c == ']') {
        if (!cur.empty()) parts.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    if (!cur.empty()) parts.push_back(cur);
    return parts;
  }
  static bool is_index(const std::string& s) {
    return !s.empty() &&
           std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  }

  void apply_override(YAML::Node& root, const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError("--set " + text + ": expected key.path=value (e.g. --set material.mu=14GPa)");
    }
    const std::string path = text.substr(0, eq);
    const std::string value_text = text.substr(eq + 1);
    const auto parts = split_path(path);
    if (parts.empty()) throw InputError("--set " + text + ": empty key path");
    YAML::Node value;
    try {
      value = YAML::Load(value_text);
    } catch (const YAML::Exception& e) {
      throw InputError("--set " + text + ": the value is not valid YAML: " + e.msg);
    }
    YAML::Node node;
    node.reset(root);
    std::string canonical;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const bool last = k + 1 == parts.size();
      const auto& part = parts[k];
      if (node.IsSequence()) {
        // More than 9 digits cannot index a scene list, and std::stoul would throw out_of_range.
        if (!is_index(part) || part.size() > 9 || std::stoul(part) >= node.size()) {
          throw InputError("--set " + text + ": '" + part + "' is not an index of the list " +
                           (canonical.empty() ? "" : canonical) + " (it has " + std::to_string(node.size()) +
                           " entries, counted from 0)");
        }
        canonical += "[" + part + "]";
        const std::size_t index = std::stoul(part);
        if (last) {
          node[index] = value;
        } else {
          YAML::Node child = node[index];
          node.reset(child);
        }
      } else {
        if (node.IsDefined() && !node.IsNull() && !node.IsMap()) {
          throw InputError("--set " + text + ": " + canonical + " is a single value, it has no key '" + part + "'");
        }
        canonical = child_path(canonical, part);
        if (last) {
          node[part] = value;
        } else {
          if (!node[part].IsDefined() || node[part].IsNull()) node[part] = YAML::Node(YAML::NodeType::Map);
          YAML::Node child = node[part];
          node.reset(child);
        }
      }
    }
    overridden_[canonical] = "--set " + text;
  }

  // ---------------------------------------------------------------- typed accessors
  // Refuses a key that the block at `path` does not accept (kBlockKeys).
  void check_keys(const YAML::Node& map, const std::string& path) {
    const std::vector<std::string>& allowed = keys_of_block(path);
    if (!map.IsMap()) fail(map, path, "expected a map of keys (" + join(allowed) + ")");
    for (const auto& kv : map) {
      // A list or map used as a key ("[a]: 1") has no string value: as<std::string>() would throw.
      if (!kv.first.IsScalar())
        fail(kv.first, path, "a key must be a plain name, not a list or map (expected one of: " + join(allowed) + ")");
      const auto key = kv.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        fail(kv.first, child_path(path, key),
             "unknown key (expected one of: " + join(allowed) + ")" + suggestion(key, allowed));
      }
    }
  }
  YAML::Node require(const YAML::Node& map, const std::string& path, const std::string& key,
                     const std::string& hint = "") {
    YAML::Node node = map[key];
    if (!node.IsDefined() || node.IsNull()) {
      fail(map, child_path(path, key), "missing required key" + (hint.empty() ? "" : " (" + hint + ")"));
    }
    return node;
  }
  std::string scalar(const YAML::Node& node, const std::string& path, const std::string& expected) {
    if (!node.IsScalar())
      fail(node, path,
           "expected " + expected + ", got a " +
               (node.IsSequence() ? "list"
                : node.IsMap()    ? "map"
                                  : "null value"));
    note_line(node, path);
    return node.Scalar();
  }
  double quantity(const YAML::Node& node, const std::string& path, const Dimension& d) {
    const auto text = scalar(node, path, d.to_string());
    try {
      return parse_quantity_as(text, d);
    } catch (const std::invalid_argument& e) {
      fail(node, path, e.what());
    }
  }
  double quantity_or(const YAML::Node& map, const std::string& path, const std::string& key, const Dimension& d,
                     double fallback) {
    const YAML::Node node = map[key];
    if (!node.IsDefined() || node.IsNull()) return fallback;
    return quantity(node, child_path(path, key), d);
  }
  int integer(const YAML::Node& node, const std::string& path) {
    const auto text = scalar(node, path, "an integer");
    try {
      std::size_t used = 0;
      const int v = std::stoi(text, &used);
      if (used == text.size()) return v;
    } catch (const std::exception&) {
    }
    fail(node, path, "\"" + text + "\" is not an integer");
  }
  std::vector<double> quantity_list(const YAML::Node& node, const std::string& path, const Dimension& d,
                                    std::size_t count) {
    if (!node.IsSequence() || node.size() != count) {
      fail(node, path, "expected a list of " + std::to_string(count) + " values (" + d.to_string() + ")");
    }
    std::vector<double> out;
    for (std::size_t k = 0; k < count; ++k) out.push_back(quantity(node[k], path + "[" + std::to_string(k) + "]", d));
    return out;
  }
  void positive(const YAML::Node& node, const std::string& path, double v, const std::string& what = "must be > 0") {
    if (!(v > 0.0)) fail(node, path, format_number(v) + " " + what);
  }
  // A name of `table` (e.g. kConeMatchNames); any other is "unknown <what> 'x' (expected a, b or c)".
  template <class E, std::size_t N>
  E enum_value(const YAML::Node& node, const std::string& path, const std::array<EnumName<E>, N>& table,
               const std::string& what) {
    const auto expected = alternatives(enum_names(table));
    const auto text = scalar(node, path, expected);
    for (const auto& entry : table) {
      if (text == entry.name) return entry.value;
    }
    fail(node, path, "unknown " + what + " '" + text + "' (expected " + expected + ")");
  }

  // ---------------------------------------------------------------- sections
  void read_header(const YAML::Node& root) {
    const auto version = integer(require(root, "", "mppm", "the scene format version: mppm: 1"), "mppm");
    if (version != 1)
      fail(root["mppm"], "mppm",
           "unsupported scene format version " + std::to_string(version) + " (this mppm reads version 1)");
    scene_.format_version = version;
    if (root["name"].IsDefined() && !root["name"].IsNull()) {
      scene_.name = scalar(root["name"], "name", "a name");
    } else {
      scene_.name = fs::path(file_).stem().string();
    }
    const auto dimension = integer(require(root, "", "dimension", "2 for plane strain or 3"), "dimension");
    if (dimension != 2 && dimension != 3)
      fail(root["dimension"], "dimension",
           std::to_string(dimension) + " is not supported (expected 2 = plane strain, or 3)");
    scene_.dimension = dimension;
    if (dimension == 2) {
      scene_.thickness =
          quantity(require(root, "", "thickness", "out-of-plane thickness of the plane-strain body, e.g. 1 mm"),
                   "thickness", dim::length);
      positive(root["thickness"], "thickness", scene_.thickness);
    } else if (root["thickness"].IsDefined()) {
      scene_.warnings.push_back(location(root["thickness"], "thickness") + ": thickness: ignored in 3-D");
    }
  }

  void read_effects(const YAML::Node& root) {
    const YAML::Node node = root["effects"];
    if (!node.IsDefined() || node.IsNull()) return;  // purely elastic non-polar model
    YAML::Node list = node;
    if (node.IsScalar()) {  // "--set effects=micropolar" or "effects: micropolar"
      // reset, not '=': assigning to a YAML::Node overwrites the node it refers to (here
      // `node` itself), which made the one-element list contain itself.
      list.reset(YAML::Node(YAML::NodeType::Sequence));
      list.push_back(node);
    }
    if (!list.IsSequence()) fail(node, "effects", "expected a list of effects (" + join(kEffectNames) + ")");
    std::set<std::string> seen;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const auto path = "effects[" + std::to_string(k) + "]";
      const auto name = scalar(list[k], path, "an effect name");
      if (!seen.insert(name).second) fail(list[k], path, "'" + name + "' is listed twice");
      if (name == "micropolar")
        scene_.effects.micropolar = true;
      else if (name == "viscoplasticity")
        scene_.effects.viscoplasticity = true;
      else if (name == "damage")
        scene_.effects.damage = true;
      else if (name == "gravity")
        scene_.effects.gravity = true;
      else if (name == "pore_fluid")
        scene_.effects.pore_fluid = true;
      else if (name == "none" && list.size() == 1) {
      } else
        fail(list[k], path,
             "unknown effect '" + name + "' (expected one of: " + join(kEffectNames) + ")" +
                 suggestion(name, kEffectNames));
    }
  }

  Selector read_selector(const YAML::Node& node, const std::string& path, bool allow_plain_name) {
    Selector s;
    if (node.IsScalar() && allow_plain_name) {
      s.physical_group = scalar(node, path, "a physical group name");
      return s;
    }
    if (!node.IsMap())
      fail(node, path, "expected a physical group name, {entities: [...]} or {box: [[x0,y0,z0],[x1,y1,z1]]}");
    check_keys(node, path);
    read_selector_keys(node, path, s);
    return s;
  }

  // Reads boundary / entities / box from a map (exactly one of them).
  void read_selector_keys(const YAML::Node& map, const std::string& path, Selector& s) {
    int given = 0;
    if (map["boundary"].IsDefined()) {
      s.physical_group = scalar(map["boundary"], child_path(path, "boundary"), "a physical group name");
      ++given;
    }
    if (map["entities"].IsDefined()) {
      const YAML::Node e = map["entities"];
      const auto p = child_path(path, "entities");
      if (!e.IsSequence() || e.size() == 0) fail(e, p, "expected a non-empty list of gmsh entity tags");
      for (std::size_t k = 0; k < e.size(); ++k) {
        const int tag = integer(e[k], p + "[" + std::to_string(k) + "]");
        if (tag <= 0) fail(e[k], p, "entity tags are positive integers");
        s.entities.push_back(tag);
      }
      ++given;
    }
    if (map["box"].IsDefined()) {
      const YAML::Node b = map["box"];
      const auto p = child_path(path, "box");
      if (!b.IsSequence() || b.size() != 2) fail(b, p, "expected [[x0, y0(, z0)], [x1, y1(, z1)]]");
      std::array<std::array<double, 3>, 2> box{};
      for (std::size_t corner = 0; corner < 2; ++corner) {
        const YAML::Node c = b[corner];
        const auto cp = p + "[" + std::to_string(corner) + "]";
        if (!c.IsSequence() || (c.size() != 2 && c.size() != 3)) fail(c, cp, "expected a corner [x, y] or [x, y, z]");
        for (std::size_t k = 0; k < 3; ++k) {
          // A 2-D box may omit z: it then spans every z.
          box[corner][k] = k < c.size() ? quantity(c[k], cp + "[" + std::to_string(k) + "]", dim::length)
                                        : (corner == 0 ? -1e300 : 1e300);
        }
      }
      for (int k = 0; k < 3; ++k) {
        if (box[0][k] > box[1][k]) fail(b, p, "the first corner must be the lower one (x0 <= x1, y0 <= y1, z0 <= z1)");
      }
      s.box = box;
      ++given;
    }
    if (given != 1) {
      fail(map, path,
           given == 0 ? "missing the selection: give one of boundary (physical group name), entities ([tags]) or box "
                        "([[x0,y0,z0],[x1,y1,z1]])"
                      : "give only one of boundary, entities or box");
    }
  }

  void read_geometry(const YAML::Node& g) {
    const std::string p = "geometry";
    check_keys(g, p);
    const auto file = scalar(require(g, p, "file", "path of a .geo .msh .step .stp .brep or .stl file"),
                             "geometry.file", "a file path");
    fs::path fp(file);
    if (fp.is_relative()) fp = fs::path(dir_) / fp;
    scene_.geometry.file = fp.lexically_normal().string();
    const auto ext = fp.extension().string();
    static const std::vector<std::string> exts{".geo", ".msh",  ".step", ".stp", ".brep",
                                               ".stl", ".STEP", ".STP",  ".STL", ".BREP"};
    if (std::find(exts.begin(), exts.end(), ext) == exts.end()) {
      fail(g["file"], "geometry.file",
           "unsupported file type '" + ext + "' (expected .geo .msh .step .stp .brep or .stl)");
    }
    if (g["unit"].IsDefined()) {
      const auto unit = scalar(g["unit"], "geometry.unit", "a length unit (m, mm, cm, um, in, ft)");
      try {
        scene_.geometry.unit = length_unit_in_metres(unit);
      } catch (const std::invalid_argument& e) {
        fail(g["unit"], "geometry.unit", e.what());
      }
    }
    scene_.geometry.spacing =
        quantity(require(g, p, "spacing", "lattice spacing dx, e.g. 0.5 mm"), "geometry.spacing", dim::length);
    positive(g["spacing"], "geometry.spacing", scene_.geometry.spacing);
    scene_.geometry.horizon_factor = quantity(require(g, p, "horizon_factor", "delta / dx, e.g. 3.015 or 4.05"),
                                              "geometry.horizon_factor", dim::none);
    if (!(scene_.geometry.horizon_factor >= 1.0)) {
      fail(g["horizon_factor"], "geometry.horizon_factor",
           format_number(scene_.geometry.horizon_factor) +
               " leaves points without neighbours (expected >= 1; 2.05 to 5 is usual)");
    }
    if (g["precracks"].IsDefined() && !g["precracks"].IsNull()) {
      const YAML::Node list = g["precracks"];
      if (!list.IsSequence())
        fail(list, "geometry.precracks",
             "expected a list of physical group names or {entities: [...]} / {box: ...} entries");
      for (std::size_t k = 0; k < list.size(); ++k) {
        scene_.geometry.precracks.push_back(
            read_selector(list[k], "geometry.precracks[" + std::to_string(k) + "]", true));
      }
    }
  }

  void read_material(const YAML::Node& m) {
    const std::string p = "material";
    check_keys(m, p);
    auto& mat = scene_.material;
    if (m["model"].IsDefined()) {
      mat.model = scalar(m["model"], "material.model", "a material model name");
      static const std::vector<std::string> models{"cosserat-elastic"};
      if (std::find(models.begin(), models.end(), mat.model) == models.end()) {
        fail(m["model"], "material.model",
             "unknown model '" + mat.model + "' (expected one of: " + join(models) +
                 "; viscoplasticity is an effect with its own block material.viscoplasticity)" +
                 suggestion(mat.model, models));
      }
    }
    mat.density =
        quantity(require(m, p, "density", "skeleton density, e.g. 2650 kg/m^3"), "material.density", dim::density);
    positive(m["density"], "material.density", mat.density);
    mat.solid_fraction = quantity_or(m, p, "solid_fraction", dim::none, 1.0);
    if (!(mat.solid_fraction > 0.0 && mat.solid_fraction <= 1.0)) {
      fail(m["solid_fraction"], "material.solid_fraction",
           format_number(mat.solid_fraction) + " is not a volume fraction (expected 0 < phi <= 1)");
    }
    mat.lambda = quantity(require(m, p, "lambda", "Lame constant, e.g. 14 GPa"), "material.lambda", dim::pressure);
    mat.mu = quantity(require(m, p, "mu", "shear modulus, e.g. 14 GPa"), "material.mu", dim::pressure);
    positive(m["mu"], "material.mu", mat.mu);
    const int d = scene_.dimension;
    if (!(mat.lambda + 2.0 * mat.mu / d > 0.0)) {
      fail(m["lambda"], "material.lambda",
           "lambda + 2 mu / d = " + format_number(mat.lambda + 2.0 * mat.mu / d) + " must be > 0 (bulk modulus)");
    }
    const bool polar = scene_.effects.micropolar;
    const std::vector<std::string> polar_keys{"mu_c", "couple_moduli", "length_scale"};
    if (polar) {
      mat.mu_c = quantity(require(m, p, "mu_c", "Cosserat couple modulus, e.g. 4.667 GPa (micropolar is on)"),
                          "material.mu_c", dim::pressure);
      if (mat.mu_c < 0.0) fail(m["mu_c"], "material.mu_c", format_number(mat.mu_c) + " must be >= 0");
      const auto a = quantity_list(require(m, p, "couple_moduli", "[a1, a2, a3] in N (micropolar is on)"),
                                   "material.couple_moduli", dim::force, 3);
      mat.couple_moduli = {a[0], a[1], a[2]};
      if (d == 2 && !(a[2] > 0.0)) {
        fail(m["couple_moduli"], "material.couple_moduli",
             "in 2-D the bending modulus B_w = a3 must be > 0 (got " + format_number(a[2]) + " N)");
      }
      if (d == 3) {
        // Curvature energy 1/2 [(3a1+a2+a3)|sph|^2 + (a2+a3)|dev|^2 + (a2-a3)|skew|^2] must be positive.
        if (!(3 * a[0] + a[1] + a[2] > 0.0 && a[1] + a[2] > 0.0 && a[1] - a[2] >= 0.0)) {
          fail(m["couple_moduli"], "material.couple_moduli",
               "a1, a2, a3 make the curvature energy indefinite in 3-D (need 3 a1 + a2 + a3 > 0, a2 + a3 > 0 and a2 >= "
               "a3)");
        }
      }
      mat.length_scale = quantity(require(m, p, "length_scale", "micro-polar length l (mean grain size), e.g. 2 mm"),
                                  "material.length_scale", dim::length);
      positive(m["length_scale"], "material.length_scale", mat.length_scale);
    } else {
      std::vector<std::string> ignored;  // full paths; the first one's key locates the warning
      std::string first_key;
      for (const auto& k : polar_keys) {
        if (!m[k].IsDefined()) continue;
        if (first_key.empty()) first_key = k;
        ignored.push_back(child_path(p, k));
      }
      if (!ignored.empty()) {
        scene_.warnings.push_back(location(m[first_key], ignored.front()) + ": " + join(ignored) +
                                  ": ignored because the effect 'micropolar' is not listed in effects");
      }
    }
    read_damage(m);
    read_viscoplasticity(m);
    read_pore_fluid(m);
  }

  void warn_effect_off(const YAML::Node& node, const std::string& path, const std::string& effect) {
    scene_.warnings.push_back(location(node, path) + ": " + path + ": ignored because the effect '" + effect +
                              "' is not listed in effects");
  }

  // The parameter block of an effect is read only when the effect is on; given while it is off,
  // it is ignored with a warning.
  bool effect_block_wanted(const YAML::Node& node, const std::string& path, bool effect_on, const std::string& effect) {
    if (!effect_on && node.IsDefined()) warn_effect_off(node, path, effect);
    return effect_on;
  }

  void read_damage(const YAML::Node& m) {
    const YAML::Node node = m["damage"];
    const std::string p = "material.damage";
    if (!effect_block_wanted(node, p, scene_.effects.damage, "damage")) return;
    if (!node.IsDefined() || node.IsNull())
      fail(m, p, "missing: the effect 'damage' needs {critical_energy_release_rate: ..., no_fail_depth: ...}");
    check_keys(node, p);
    DamageParameters dp;
    dp.critical_energy_release_rate = quantity(require(node, p, "critical_energy_release_rate", "G_cr, e.g. 160 N/m"),
                                               p + ".critical_energy_release_rate", dim::energy_per_area);
    positive(node["critical_energy_release_rate"], p + ".critical_energy_release_rate",
             dp.critical_energy_release_rate);
    dp.no_fail_depth = quantity_or(node, p, "no_fail_depth", dim::length, 0.0);
    if (dp.no_fail_depth < 0.0) fail(node["no_fail_depth"], p + ".no_fail_depth", "must be >= 0");
    if (node["calibration"].IsDefined()) {
      dp.calibration = enum_value(node["calibration"], p + ".calibration", kDamageCalibrationNames, "calibration");
    }
    if (node["compressed_bonds"].IsDefined())
      dp.compressed_bonds =
          enum_value(node["compressed_bonds"], p + ".compressed_bonds", kCompressedBondsNames, "compressed_bonds");
    if (node["region"].IsDefined()) dp.region = read_region(node["region"], p + ".region");
    scene_.material.damage = dp;
  }

  // An effect's region: {box: [[x0, y0(, z0)], [x1, y1(, z1)]]} (the points file knows the body
  // and its boundaries, not volume groups, so a box is what can select points).
  Selector read_region(const YAML::Node& node, const std::string& path) {
    if (!node.IsMap()) fail(node, path, "expected {box: [[x0, y0(, z0)], [x1, y1(, z1)]]}");
    check_keys(node, path);
    if (!node["box"].IsDefined()) fail(node, path, "missing: box (expected {box: [[x0, y0(, z0)], [x1, y1(, z1)]]})");
    Selector s;
    read_selector_keys(node, path, s);
    return s;
  }

  void read_viscoplasticity(const YAML::Node& m) {
    const YAML::Node node = m["viscoplasticity"];
    const std::string p = "material.viscoplasticity";
    if (!effect_block_wanted(node, p, scene_.effects.viscoplasticity, "viscoplasticity")) return;
    if (!node.IsDefined() || node.IsNull()) {
      fail(m, p,
           "missing: the effect 'viscoplasticity' needs {friction_angle, dilatancy_angle, cohesion, hardening, "
           "viscosity}");
    }
    check_keys(node, p);
    ViscoplasticParameters vp;
    if (node["model"].IsDefined()) vp.model = scalar(node["model"], p + ".model", "a model name");
    vp.friction_angle = quantity(require(node, p, "friction_angle", "e.g. 35 deg"), p + ".friction_angle", dim::angle);
    vp.dilatancy_angle =
        quantity(require(node, p, "dilatancy_angle", "e.g. 15 deg"), p + ".dilatancy_angle", dim::angle);
    const double right = std::numbers::pi / 2;
    if (!(vp.friction_angle >= 0.0 && vp.friction_angle < right))
      fail(node["friction_angle"], p + ".friction_angle", "must be in [0, 90) deg");
    if (!(vp.dilatancy_angle >= 0.0 && vp.dilatancy_angle < right))
      fail(node["dilatancy_angle"], p + ".dilatancy_angle", "must be in [0, 90) deg");
    if (vp.dilatancy_angle > vp.friction_angle) {
      scene_.warnings.push_back(
          location(node["dilatancy_angle"], p) + ": " + p +
          ".dilatancy_angle: larger than the friction angle (the flow dilates more than an associated one)");
    }
    vp.cohesion = quantity(require(node, p, "cohesion", "c0, e.g. 0.35 MPa"), p + ".cohesion", dim::pressure);
    if (vp.cohesion < 0.0) fail(node["cohesion"], p + ".cohesion", "must be >= 0");
    vp.hardening = quantity_or(node, p, "hardening", dim::pressure, 0.0);
    vp.viscosity = quantity(require(node, p, "viscosity", "eta, e.g. 0.01 MPa*s"), p + ".viscosity", dim::viscosity);
    if (vp.viscosity < 0.0) fail(node["viscosity"], p + ".viscosity", "must be >= 0 (0 = rate-independent)");
    // A softening cohesion is floored so the cone keeps an apex; 1 % of c0 unless given.
    vp.residual_cohesion = quantity_or(node, p, "residual_cohesion", dim::pressure, 0.01 * vp.cohesion);
    if (vp.residual_cohesion < 0.0 || vp.residual_cohesion > vp.cohesion) {
      fail(node["residual_cohesion"], p + ".residual_cohesion", "must be in [0, cohesion]");
    }
    if (node["cone_match"].IsDefined()) {
      vp.cone_match = enum_value(node["cone_match"], p + ".cone_match", kConeMatchNames, "match");
    }
    if (node["region"].IsDefined()) vp.region = read_region(node["region"], p + ".region");
    scene_.material.viscoplasticity = vp;
  }

  // The pore fluid (docs/theory.md section 12), saturated unless `retention` is given. The solver
  // refuses the unsaturated model at its start while its coupling is not built (solve_run.cpp).
  void read_pore_fluid(const YAML::Node& m) {
    const YAML::Node node = m["pore_fluid"];
    const std::string p = "material.pore_fluid";
    if (!effect_block_wanted(node, p, scene_.effects.pore_fluid, "pore_fluid")) return;
    if (!node.IsDefined() || node.IsNull())
      fail(m, p, "missing: the effect 'pore_fluid' needs {permeability, fluid_viscosity, biot_modulus}");
    check_keys(node, p);
    PoreFluidParameters fluid;
    fluid.permeability = quantity(require(node, p, "permeability", "intrinsic permeability k, e.g. 1e-12 m^2"),
                                  p + ".permeability", dim::area);
    positive(node["permeability"], p + ".permeability", fluid.permeability);
    fluid.fluid_viscosity = quantity(require(node, p, "fluid_viscosity", "mu_f, e.g. 1 mPa*s for water"),
                                     p + ".fluid_viscosity", dim::viscosity);
    positive(node["fluid_viscosity"], p + ".fluid_viscosity", fluid.fluid_viscosity);
    fluid.fluid_density = quantity_or(node, p, "fluid_density", dim::density, 1000.0);
    if (!(fluid.fluid_density >= 0.0))
      fail(node["fluid_density"], p + ".fluid_density", format_number(fluid.fluid_density) + " must be >= 0");
    fluid.biot_coefficient = quantity_or(node, p, "biot_coefficient", dim::none, 1.0);
    check_biot_coefficient(node["biot_coefficient"], p + ".biot_coefficient", fluid.biot_coefficient);
    fluid.biot_modulus =
        quantity(require(node, p, "biot_modulus", "M, e.g. 2 GPa"), p + ".biot_modulus", dim::pressure);
    positive(node["biot_modulus"], p + ".biot_modulus", fluid.biot_modulus);
    read_initial_pressure(node, p, fluid);
    if (node["retention"].IsDefined()) fluid.retention = read_retention(node["retention"], p + ".retention");
    scene_.material.pore_fluid = fluid;
  }

  // {model: van_genuchten, air_entry_pressure, n, residual_saturation (0 unless given)}.
  RetentionParameters read_retention(const YAML::Node& node, const std::string& p) {
    check_keys(node, p);
    RetentionParameters r;
    r.model = scalar(require(node, p, "model", "van_genuchten"), p + ".model", "a model name");
    if (r.model != "van_genuchten")
      fail(node["model"], p + ".model", "unknown model '" + r.model + "' (expected van_genuchten)");
    r.air_entry_pressure =
        quantity(require(node, p, "air_entry_pressure", "p_e, e.g. 10 kPa"), p + ".air_entry_pressure", dim::pressure);
    positive(node["air_entry_pressure"], p + ".air_entry_pressure", r.air_entry_pressure);
    r.n = quantity(require(node, p, "n", "van Genuchten's n > 1, e.g. 2"), p + ".n", dim::none);
    if (!(r.n > 1.0)) fail(node["n"], p + ".n", format_number(r.n) + " must be > 1 (m = 1 - 1/n > 0)");
    r.residual_saturation = quantity_or(node, p, "residual_saturation", dim::none, 0.0);
    if (!(r.residual_saturation >= 0.0 && r.residual_saturation < 1.0)) {
      fail(node["residual_saturation"], p + ".residual_saturation",
           format_number(r.residual_saturation) + " is out of range (expected 0 <= residual_saturation < 1)");
    }
    return r;
  }

  // n0 < b <= 1: b = 1 - K / K_s for a skeleton no stiffer than its grains (b = 1: rigid grains),
  // and the grains' share (b - n0) / K_s of the storage 1 / M = n0 / K_f + (b - n0) / K_s is positive.
  void check_biot_coefficient(const YAML::Node& node, const std::string& path, double b) {
    const double porosity = scene_.material.porosity();
    if (b > porosity && b <= 1.0) return;
    fail(node, path,
         format_number(b) + " is out of range (expected porosity < b <= 1, with the porosity n0 = 1 - " +
             "material.solid_fraction = " + format_number(porosity) + ")");
  }

  // A constant pressure (compression positive; 0 Pa unless given), or `hydrostatic` under gravity
  // below the level `free_surface` (the fluid at rest: docs/theory.md section 12).
  void read_initial_pressure(const YAML::Node& block, const std::string& p, PoreFluidParameters& fluid) {
    const YAML::Node node = block["initial_pressure"];
    const YAML::Node surface = block["free_surface"];
    const std::string path = p + ".initial_pressure";
    if (node.IsDefined() && node.IsScalar() && node.Scalar() == "hydrostatic") {
      if (!scene_.effects.gravity)
        fail(node, path, "hydrostatic needs the effect 'gravity' (the fluid's weight sets the pressure)");
      fluid.free_surface = quantity(require(block, p, "free_surface", "the level of the water table, e.g. 1 m"),
                                    p + ".free_surface", dim::length);
      return;
    }
    if (surface.IsDefined())
      fail(surface, p + ".free_surface", "goes with initial_pressure: hydrostatic (the constant pressure has none)");
    if (!node.IsDefined() || node.IsNull()) return;
    fluid.initial_pressure = quantity(node, path, dim::pressure);  // finite: the quantity parser refuses inf and nan
  }

  void read_gravity(const YAML::Node& root) {
    const int d = scene_.dimension;
    scene_.gravity = d == 2 ? std::array<double, 3>{0.0, -9.81, 0.0} : std::array<double, 3>{0.0, 0.0, -9.81};
    const YAML::Node node = root["gravity"];
    if (!node.IsDefined() || node.IsNull()) return;
    if (!scene_.effects.gravity) {
      warn_effect_off(node, "gravity", "gravity");
      return;
    }
    const auto g = quantity_list(node, "gravity", dim::acceleration, static_cast<std::size_t>(d));
    scene_.gravity = {g[0], g[1], d == 3 ? g[2] : 0.0};
  }

  // The unit of a condition's value (a fluid flux is an inflow velocity, volume per area and time).
  static Dimension value_unit(BoundaryType type) {
    return type == BoundaryType::velocity || type == BoundaryType::fluid_flux ? dim::velocity
           : type == BoundaryType::displacement                               ? dim::length
                                                                              : dim::pressure;
  }
  // The unit of a micro-rotation condition: a rate on a velocity layer, an angle on a displacement one.
  static Dimension rotation_unit(BoundaryType type) {
    return type == BoundaryType::velocity ? Dimension{{0, 0, -1}, true} : dim::angle;
  }
  std::size_t rotation_components() const { return scene_.dimension == 2 ? 1 : 3; }

  // A component written `free` (or left empty) is not prescribed: kinematic conditions only.
  bool is_free_component(const YAML::Node& comp, const std::string& path, const BoundaryCondition& bc) {
    const bool free = comp.IsNull() || (comp.IsScalar() && comp.Scalar() == "free");
    if (free && !is_kinematic(bc.type)) fail(comp, path, "only velocity and displacement components can be free");
    return free;
  }

  // Reads `value`, `ramp`, `history` of one boundary condition into a History, then its rotation.
  void read_boundary_value(const YAML::Node& node, const std::string& p, BoundaryCondition& bc) {
    const std::size_t n = value_components(bc.type, scene_.dimension);
    const Dimension unit = value_unit(bc.type);
    std::vector<double> value(n, 0.0);
    bc.constrained.assign(n, true);
    const YAML::Node v = node["value"];
    const YAML::Node ramp = node["ramp"];
    const YAML::Node history = node["history"];
    if (v.IsDefined()) {
      value = read_value_components(v, p + ".value", bc, unit);
    } else if (!history.IsDefined()) {
      fail(node, p + ".value", "missing: give value (with an optional ramp) or history");
    }
    if (ramp.IsDefined() && history.IsDefined()) fail(ramp, p + ".ramp", "give either ramp or history, not both");
    if (ramp.IsDefined()) {
      const double t0 = quantity(ramp, p + ".ramp", dim::time);
      positive(ramp, p + ".ramp", t0);
      bc.value.times = {0.0, t0};
      bc.value.values = {std::vector<double>(n, 0.0), value};
    } else if (history.IsDefined()) {
      read_value_history(history, p + ".history", v.IsDefined(), value, bc, unit);
    } else {
      bc.value.times = {0.0};
      bc.value.values = {value};
    }
    read_boundary_rotation(node, p, bc);
  }

  // `value`: one pressure (pressure, pore_pressure) or inflow (fluid_flux), or one entry per
  // component (kinematic components may be free).
  std::vector<double> read_value_components(const YAML::Node& v, const std::string& path, BoundaryCondition& bc,
                                            const Dimension& unit) {
    const std::size_t n = bc.constrained.size();
    std::vector<double> value(n, 0.0);
    if (n == 1 && (bc.type == BoundaryType::pressure || is_fluid(bc.type))) {
      is_free_component(v, path, bc);  // refused: only kinematic components can be free
      if (!v.IsScalar())
        fail(v, path, "expected one value, " + unit.to_string() + ", for a " + to_string(bc.type) + " condition");
      value[0] = quantity(v, path, unit);
      return value;
    }
    if (!v.IsSequence() || v.size() != n)
      fail(v, path, "expected a list of " + std::to_string(n) + " components (" + unit.to_string() + ")");
    for (std::size_t c = 0; c < n; ++c) {
      const auto cp = path + "[" + std::to_string(c) + "]";
      const YAML::Node comp = v[c];
      if (is_free_component(comp, cp, bc)) {
        bc.constrained[c] = false;
        note_line(comp, cp);
      } else {
        value[c] = quantity(comp, cp, unit);
      }
    }
    return value;
  }

  // `history`: with a `value` (scaled), rows are [t, factor]; without, [t, v] (scalar) or [t, [v...]].
  void read_value_history(const YAML::Node& history, const std::string& path, bool scaled,
                          const std::vector<double>& value, BoundaryCondition& bc, const Dimension& unit) {
    const std::size_t n = value.size();
    if (!history.IsSequence() || history.size() == 0) fail(history, path, "expected a list of rows [t, v]");
    for (std::size_t r = 0; r < history.size(); ++r) {
      const auto rp = path + "[" + std::to_string(r) + "]";
      const YAML::Node row = history[r];
      if (!row.IsSequence() || row.size() != 2) fail(row, rp, scaled ? "expected [t, factor]" : "expected [t, value]");
      const double t = quantity(row[0], rp + "[0]", dim::time);
      if (!bc.value.times.empty() && t < bc.value.times.back()) fail(row, rp, "times must not decrease");
      std::vector<double> rowv(n);
      if (scaled) {
        const double factor = quantity(row[1], rp + "[1]", dim::none);
        for (std::size_t c = 0; c < n; ++c) rowv[c] = factor * value[c];
      } else if (n == 1 && row[1].IsScalar()) {
        is_free_component(row[1], rp + "[1]", bc);  // refused: only kinematic components can be free
        rowv[0] = quantity(row[1], rp + "[1]", unit);
      } else {
        const YAML::Node vals = row[1];
        if (!vals.IsSequence() || vals.size() != n)
          fail(vals, rp + "[1]", "expected a list of " + std::to_string(n) + " components (" + unit.to_string() + ")");
        for (std::size_t c = 0; c < n; ++c) {
          const YAML::Node comp = vals[c];
          const bool free = is_free_component(comp, rp, bc);
          if (r > 0 && free == bc.constrained[c])
            fail(comp, rp, "a component is free in some rows and prescribed in others");
          bc.constrained[c] = !free;
          rowv[c] = free ? 0.0 : quantity(comp, rp + "[1][" + std::to_string(c) + "]", unit);
        }
      }
      bc.value.times.push_back(t);
      bc.value.values.push_back(rowv);
    }
  }

  // Rotation on a kinematic layer: a full `rotation_history`, or `rotation` / `rotation_rate`
  // following the same time profile as the value.
  void read_boundary_rotation(const YAML::Node& node, const std::string& p, BoundaryCondition& bc) {
    if (!is_kinematic(bc.type))
      for (const char* key : {"rotation", "rotation_rate", "rotation_history"})
        if (node[key].IsDefined())
          fail(node[key], p + "." + key,
               std::string("micro-rotation can be prescribed only on velocity or displacement conditions (not on a ") +
                   to_string(bc.type) + " condition)");
    const char* rotation_key = bc.type == BoundaryType::velocity ? "rotation_rate" : "rotation";
    const char* other_key = bc.type == BoundaryType::velocity ? "rotation" : "rotation_rate";
    if (node[other_key].IsDefined()) {
      fail(node[other_key], p + "." + other_key,
           std::string("does not fit a ") + to_string(bc.type) + " condition (use " + rotation_key + ")");
    }
    const YAML::Node rot = node[rotation_key];
    const YAML::Node rot_history = node["rotation_history"];
    if (rot_history.IsDefined()) {
      const auto rp = p + ".rotation_history";
      if (rot.IsDefined()) fail(rot_history, rp, std::string("give either ") + rotation_key + " or rotation_history");
      if (!is_kinematic(bc.type))
        fail(rot_history, rp, "micro-rotation can be prescribed only on velocity or displacement conditions");
      const History h = read_rotation_history(rot_history, rp, bc);
      if (scene_.effects.micropolar)
        bc.rotation = h;
      else
        warn_effect_off(rot_history, rp, "micropolar");
      return;
    }
    if (rot.IsDefined()) read_rotation_value(node, rot, p, p + "." + rotation_key, bc);
  }

  // Full rotation history [[t, r], ...] (written by the resolved-scene writer).
  History read_rotation_history(const YAML::Node& rot_history, const std::string& rp, const BoundaryCondition& bc) {
    if (!rot_history.IsSequence() || rot_history.size() == 0)
      fail(rot_history, rp, "expected a list of rows [t, rotation]");
    const Dimension rd = rotation_unit(bc.type);
    const std::size_t nr = rotation_components();
    History h;
    for (std::size_t r = 0; r < rot_history.size(); ++r) {
      const auto rowp = rp + "[" + std::to_string(r) + "]";
      const YAML::Node row = rot_history[r];
      if (!row.IsSequence() || row.size() != 2) fail(row, rowp, "expected [t, rotation]");
      const double t = quantity(row[0], rowp + "[0]", dim::time);
      if (!h.times.empty() && t < h.times.back()) fail(row, rowp, "times must not decrease");
      h.times.push_back(t);
      if (nr == 1 && row[1].IsScalar())
        h.values.push_back({quantity(row[1], rowp + "[1]", rd)});
      else
        h.values.push_back(quantity_list(row[1], rowp + "[1]", rd, nr));
    }
    return h;
  }

  // `rotation` / `rotation_rate`: one value, scaled by the rows of the value's ramp or history.
  void read_rotation_value(const YAML::Node& node, const YAML::Node& rot, const std::string& p, const std::string& rp,
                           BoundaryCondition& bc) {
    if (!is_kinematic(bc.type))
      fail(rot, rp, "micro-rotation can be prescribed only on velocity or displacement conditions");
    if (!scene_.effects.micropolar) {
      warn_effect_off(rot, rp, "micropolar");
      return;
    }
    const Dimension rd = rotation_unit(bc.type);
    const std::size_t nr = rotation_components();
    std::vector<double> r(nr);
    if (nr == 1 && rot.IsScalar())
      r[0] = quantity(rot, rp, rd);
    else
      r = quantity_list(rot, rp, rd, nr);
    const YAML::Node ramp = node["ramp"];
    const YAML::Node history = node["history"];
    History h;
    if (ramp.IsDefined() || (history.IsDefined() && node["value"].IsDefined())) {
      h.times = bc.value.times;
      for (std::size_t row = 0; row < h.times.size(); ++row) {
        // factor of this row relative to the value (ramp: 0 then 1).
        double factor = ramp.IsDefined() ? (row == 0 ? 0.0 : 1.0) : quantity(history[row][1], p, dim::none);
        std::vector<double> rv(nr);
        for (std::size_t c = 0; c < nr; ++c) rv[c] = factor * r[c];
        h.values.push_back(rv);
      }
    } else {
      h.times = {0.0};
      h.values = {r};
    }
    bc.rotation = h;
  }

  void read_boundary_conditions(const YAML::Node& root) {
    const YAML::Node list = root["boundary_conditions"];
    if (!list.IsDefined() || list.IsNull()) return;
    if (!list.IsSequence())
      fail(list, "boundary_conditions", "expected a list of conditions {boundary: ..., type: ..., value: ...}");
    std::set<std::string> names;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const auto p = "boundary_conditions[" + std::to_string(k) + "]";
      const YAML::Node node = list[k];
      check_keys(node, p);
      BoundaryCondition bc;
      bc.line = node.Mark().line + 1;
      read_selector_keys(node, p, bc.selector);
      bc.type = read_boundary_type(node, p);
      read_boundary_value(node, p, bc);
      read_boundary_depth(node, p, bc);
      bc.name = boundary_label(node, p, bc, k);
      if (!names.insert(bc.name).second) {
        fail(node, p + ".name",
             "the label '" + bc.name +
                 "' is used by an earlier condition (give each a distinct name: it labels load.csv)");
      }
      scene_.boundary_conditions.push_back(bc);
    }
    refuse_two_fluid_conditions_on_one_boundary(list);
  }

  BoundaryType read_boundary_type(const YAML::Node& node, const std::string& p) {
    const auto type = scalar(require(node, p, "type",
                                     "velocity, displacement, traction, pressure, pore_pressure or "
                                     "fluid_flux"),
                             p + ".type", "a condition type");
    static const std::vector<std::pair<std::string, BoundaryType>> known{
        {"velocity", BoundaryType::velocity},           {"displacement", BoundaryType::displacement},
        {"traction", BoundaryType::traction},           {"pressure", BoundaryType::pressure},
        {"pore_pressure", BoundaryType::pore_pressure}, {"fluid_flux", BoundaryType::fluid_flux}};
    std::vector<std::string> names;
    for (const auto& [name, value] : known) {
      if (name != type) {
        names.push_back(name);
        continue;
      }
      // The fluid's conditions need its state: without the effect there is no pressure to prescribe.
      if (is_fluid(value) && !scene_.effects.pore_fluid)
        fail(node["type"], p + ".type", type + " needs the effect pore_fluid (add it to effects)");
      return value;
    }
    fail(node["type"], p + ".type",
         "unknown type '" + type + "' (expected one of: " + join(names) + ")" + suggestion(type, names));
  }

  // `depth`: the loaded layer of a traction, pressure or fluid flux (default dx).
  void read_boundary_depth(const YAML::Node& node, const std::string& p, BoundaryCondition& bc) {
    if (!node["depth"].IsDefined()) {
      bc.traction_depth = scene_.geometry.spacing;
      return;
    }
    if (!has_loaded_depth(bc.type))
      fail(node["depth"], p + ".depth",
           std::string("only traction, pressure and fluid_flux conditions have a loaded depth (the layer of a ") +
               to_string(bc.type) + " condition is as deep as the horizon)");
    bc.traction_depth = quantity(node["depth"], p + ".depth", dim::length);
    positive(node["depth"], p + ".depth", bc.traction_depth);
  }

  // `name`, else the physical group (with _pore_pressure / _fluid_flux appended for the fluid's
  // conditions, so that a face can carry a load and a fluid condition under distinct labels), else bcK.
  std::string boundary_label(const YAML::Node& node, const std::string& p, const BoundaryCondition& bc, std::size_t k) {
    if (node["name"].IsDefined()) return scalar(node["name"], p + ".name", "a label");
    if (bc.selector.physical_group.empty()) return "bc" + std::to_string(k + 1);
    return is_fluid(bc.type) ? bc.selector.physical_group + "_" + to_string(bc.type) : bc.selector.physical_group;
  }

  // A boundary is drained or takes an inflow, not both, and not twice: two fluid conditions with
  // the same selection would prescribe the fluid there twice over.
  void refuse_two_fluid_conditions_on_one_boundary(const YAML::Node& list) {
    const auto& conditions = scene_.boundary_conditions;
    for (std::size_t k = 0; k < conditions.size(); ++k)
      for (std::size_t j = 0; j < k; ++j) {
        if (!is_fluid(conditions[k].type) || !is_fluid(conditions[j].type)) continue;
        if (conditions[k].selector.fingerprint() != conditions[j].selector.fingerprint()) continue;
        fail(list[k], "boundary_conditions[" + std::to_string(k) + "]",
             std::string("a second fluid condition (") + to_string(conditions[k].type) + ") on " +
                 conditions[k].selector.describe() + ", which boundary_conditions[" + std::to_string(j) + "] ('" +
                 conditions[j].name + "') already gives a " + to_string(conditions[j].type) +
                 " (a boundary is drained or takes an inflow, once)");
      }
  }

  void read_time(const YAML::Node& t) {
    const std::string p = "time";
    check_keys(t, p);
    scene_.time.end = quantity(require(t, p, "end", "end time, e.g. 60 us"), "time.end", dim::time);
    positive(t["end"], "time.end", scene_.time.end);
    const YAML::Node step = t["step"];
    if (step.IsDefined() && !(step.IsScalar() && step.Scalar() == "auto")) {
      scene_.time.step = quantity(step, "time.step", dim::time);
      positive(step, "time.step", *scene_.time.step);
      if (*scene_.time.step > scene_.time.end) fail(step, "time.step", "is longer than time.end");
      if (t["safety"].IsDefined())
        scene_.warnings.push_back(location(t["safety"], "time.safety") +
                                  ": time.safety: ignored because time.step is given");
    }
    scene_.time.safety = quantity_or(t, p, "safety", dim::none, 0.8);
    if (!(scene_.time.safety > 0.0 && scene_.time.safety <= 1.0))
      fail(t["safety"], "time.safety", format_number(scene_.time.safety) + " must be in (0, 1]");
  }

  void read_output(const YAML::Node& o) {
    auto& out = scene_.output;
    out.interval = scene_.time.end / 20.0;
    out.fields.clear();
    out.fields.push_back("displacement");
    if (scene_.effects.micropolar) out.fields.push_back("rotation");
    if (scene_.effects.damage) out.fields.push_back("damage");
    if (scene_.effects.damage && scene_.dimension == 3) out.fields.push_back("crack_area");
    if (scene_.effects.viscoplasticity) out.fields.push_back("plastic_shear_strain");
    if (scene_.effects.pore_fluid) out.fields.push_back("pore_pressure");
    if (!o.IsDefined() || o.IsNull()) return;
    const std::string p = "output";
    check_keys(o, p);
    out.interval = quantity_or(o, p, "interval", dim::time, out.interval);
    out.load_interval = quantity_or(o, p, "load_interval", dim::time, 0.0);
    out.checkpoint_interval = quantity_or(o, p, "checkpoint_interval", dim::time, 0.0);
    for (const char* key : {"interval", "load_interval", "checkpoint_interval"}) {
      if (o[key].IsDefined() && quantity(o[key], p + "." + key, dim::time) < 0.0)
        fail(o[key], p + "." + key, "must be >= 0");
    }
    if (o["fields"].IsDefined()) {
      const YAML::Node f = o["fields"];
      if (!f.IsSequence()) fail(f, "output.fields", "expected a list of field names");
      std::vector<std::string> known;
      for (const auto& [name, effect] : kOutputFields) known.push_back(name);
      out.fields.clear();
      for (std::size_t k = 0; k < f.size(); ++k) {
        const auto fp = "output.fields[" + std::to_string(k) + "]";
        const auto name = scalar(f[k], fp, "a field name");
        const auto it =
            std::find_if(kOutputFields.begin(), kOutputFields.end(), [&](const auto& e) { return e.first == name; });
        if (it == kOutputFields.end())
          fail(f[k], fp,
               "unknown field '" + name + "' (expected one of: " + join(known) + ")" + suggestion(name, known));
        const auto& effect = it->second;
        const bool on = effect.empty() || (effect == "micropolar" && scene_.effects.micropolar) ||
                        (effect == "damage" && scene_.effects.damage) ||
                        (effect == "viscoplasticity" && scene_.effects.viscoplasticity) ||
                        (effect == "pore_fluid" && scene_.effects.pore_fluid);
        if (!on) {
          scene_.warnings.push_back(location(f[k], fp) + ": " + fp + ": '" + name +
                                    "' is not written because the effect '" + effect + "' is off");
          continue;
        }
        if (name == "crack_area" && scene_.dimension != 3) {  // 2-D runs measure the crack length instead
          scene_.warnings.push_back(location(f[k], fp) + ": " + fp + ": '" + name +
                                    "' is written in 3-D runs only (2-D runs measure the crack length)");
          continue;
        }
        if (std::find(out.fields.begin(), out.fields.end(), name) == out.fields.end()) out.fields.push_back(name);
      }
    }
  }

  void read_numerics(const YAML::Node& n) {
    if (!n.IsDefined() || n.IsNull()) return;
    const std::string p = "numerics";
    check_keys(n, p);
    auto& num = scene_.numerics;
    num.stabilization = quantity_or(n, p, "stabilization", dim::none, num.stabilization);
    if (num.stabilization < 0.0)
      fail(n["stabilization"], "numerics.stabilization", "must be >= 0 (0 disables the zero-energy-mode control)");
    num.damping = quantity_or(n, p, "damping", dim::rate, num.damping);
    if (num.damping < 0.0) fail(n["damping"], "numerics.damping", "must be >= 0");
    num.energy_check_tolerance = quantity_or(n, p, "energy_check_tolerance", dim::none, num.energy_check_tolerance);
    positive(n["energy_check_tolerance"], "numerics.energy_check_tolerance", num.energy_check_tolerance);
    if (n["energy_check_start_step"].IsDefined()) {
      num.energy_check_start_step = integer(n["energy_check_start_step"], "numerics.energy_check_start_step");
      if (num.energy_check_start_step < 0)
        fail(n["energy_check_start_step"], "numerics.energy_check_start_step", "must be >= 0");
    }
    num.detach_energy_rise = quantity_or(n, p, "detach_energy_rise", dim::none, num.detach_energy_rise);
    if (num.detach_energy_rise < 0.0) {
      fail(n["detach_energy_rise"], "numerics.detach_energy_rise",
           format_number(num.detach_energy_rise) + " must be >= 0 (a share of the stored energy)");
    }
    num.overload_factor = quantity_or(n, p, "overload_factor", dim::none, num.overload_factor);
    positive(n["overload_factor"], "numerics.overload_factor", num.overload_factor,
             "must be > 0 (a multiple of the breaking energy)");
    num.damaged_frequency_ratio = quantity_or(n, p, "damaged_frequency_ratio", dim::none, num.damaged_frequency_ratio);
    if (!(num.damaged_frequency_ratio >= 1.0)) {
      fail(n["damaged_frequency_ratio"], "numerics.damaged_frequency_ratio",
           format_number(num.damaged_frequency_ratio) +
               " must be >= 1 (omega_max^2 is at least the largest point block)");
    }
    if (n["flow_integration"].IsDefined()) {
      num.flow_integration =
          enum_value(n["flow_integration"], "numerics.flow_integration", kFlowIntegrationNames, "flow integration");
    }
    if (n["step_estimate"].IsDefined()) {
      num.step_estimate =
          enum_value(n["step_estimate"], "numerics.step_estimate", kStepEstimateNames, "critical step estimate");
    }
  }
};

}  // namespace

std::vector<std::string> scene_key_paths() {
  std::vector<std::string> paths;
  for (const auto& [block, keys] : kBlockKeys) {
    for (const auto& key : keys) paths.push_back(block.empty() ? key : block + "." + key);
  }
  return paths;
}

std::vector<std::string> EffectSet::names() const {
  std::vector<std::string> out;
  if (micropolar) out.push_back("micropolar");
  if (viscoplasticity) out.push_back("viscoplasticity");
  if (damage) out.push_back("damage");
  if (gravity) out.push_back("gravity");
  if (pore_fluid) out.push_back("pore_fluid");
  return out;
}

namespace {
// "box [[x0, y0(, z0)], [x1, y1(, z1)]] m" with `digits` significant digits; a 2-D box spans
// every z (|z| ~ 1e300), which is left out.
std::string box_text(const std::array<std::array<double, 3>, 2>& box, int digits) {
  std::ostringstream out;
  out.precision(digits);
  out << "box [";
  for (int k = 0; k < 2; ++k) {
    out << (k ? ", [" : "[") << box[k][0] << ", " << box[k][1];
    if (std::abs(box[k][2]) < 1e299) out << ", " << box[k][2];
    out << "]";
  }
  out << "] m";
  return out.str();
}
}  // namespace

std::string Selector::describe() const {
  if (!physical_group.empty()) return "'" + physical_group + "'";
  if (!entities.empty()) {
    std::ostringstream out;
    out << "entities [";
    for (std::size_t k = 0; k < entities.size(); ++k) out << (k ? ", " : "") << entities[k];
    out << "]";
    return out.str();
  }
  return box ? box_text(*box, 6) : std::string();
}

std::string Selector::fingerprint() const {
  if (!physical_group.empty() || !entities.empty() || !box) return describe();
  return box_text(*box, 17);
}

const char* to_string(BoundaryType type) {
  switch (type) {
    case BoundaryType::velocity:
      return "velocity";
    case BoundaryType::displacement:
      return "displacement";
    case BoundaryType::traction:
      return "traction";
    case BoundaryType::pressure:
      return "pressure";
    case BoundaryType::pore_pressure:
      return "pore_pressure";
    case BoundaryType::fluid_flux:
      return "fluid_flux";
  }
  return "?";
}

double Material::micro_inertia() const {
  return 0.5 * std::numbers::pi * partial_density() * length_scale * length_scale;
}

double Material::bending_modulus(int dimension) const {
  // 2-D: a3 (docs/theory.md section 5). 3-D: a2, the modulus of m_zx = a2 w_z,x, i.e. of a rotation that
  // varies across its own axis (the transverse twist the stabilization controls).
  return dimension == 2 ? couple_moduli[2] : couple_moduli[1];
}

std::string Scene::where(const std::string& key_path) const {
  // The key itself, else the nearest enclosing key that has a line.
  std::string p = key_path;
  while (!p.empty()) {
    if (auto it = key_lines.find(p); it != key_lines.end())
      return path + ":" + std::to_string(it->second) + ": " + key_path;
    const auto cut = p.find_last_of(".[");
    if (cut == std::string::npos) break;
    p = p.substr(0, cut);
  }
  for (const auto& [k, line] : key_lines) {
    if (k.rfind(key_path, 0) == 0) return path + ":" + std::to_string(line) + ": " + key_path;
  }
  return path + ": " + key_path;
}

Scene parse_scene(const std::string& text, const std::string& path, const std::vector<std::string>& overrides) {
  const auto dir = std::filesystem::absolute(std::filesystem::path(path)).parent_path().string();
  SceneReader reader(path, dir);
  return reader.read(text, overrides);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": scene file not found");
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": is a directory, expected a scene file (.yaml)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), path, overrides);
}

}  // namespace mppm
