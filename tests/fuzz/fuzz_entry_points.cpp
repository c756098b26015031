// The untrusted-input entry points shared by the libFuzzer targets and the corpus test, and
// the contract checks applied to every outcome (see fuzz_entry_points.hpp).
#include "tests/fuzz/fuzz_entry_points.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "common/input_error.hpp"
#include "common/point_cloud.hpp"
#include "common/scene.hpp"
#include "common/snapshot_file.hpp"
#include "common/units.hpp"

namespace mppm::fuzz {
namespace {

[[noreturn]] void violated(const std::string& what) { throw ContractViolation(what); }

// An InputError must say where: the file, or the `--set` option that is wrong.
void require_message_names(const std::string& message, const std::string& path) {
  if (message.find(path) == std::string::npos && message.rfind("--set ", 0) != 0) {
    violated("error message names neither the file '" + path + "' nor a --set option: " + message);
  }
}

// A private scratch file of this process (never next to the input: that may be the source tree).
std::string temporary_path(const std::string& suffix) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/mppm_fuzz_" + std::to_string(::getpid()) + suffix;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Outcome scene_attempt(std::string_view text, const std::string& path, const std::vector<std::string>& overrides) {
  Scene scene;
  try {
    scene = parse_scene(std::string(text), path, overrides);
  } catch (const InputError& e) {
    require_message_names(e.what(), path);
    return {false, e.what()};
  }
  // The resolved scene is what restart and postprocessing read back (scene_writer.cpp): it
  // must parse, and writing it again must give the same text (a fixed point).
  const std::string resolved = resolved_scene_yaml(scene);
  std::string again;
  try {
    again = resolved_scene_yaml(parse_scene(resolved, path));
  } catch (const InputError& e) {
    violated(std::string("the resolved scene of an accepted scene does not read back: ") + e.what() +
             "\n--- resolved scene ---\n" + resolved);
  }
  if (again != resolved) {
    violated("the resolved scene is not a fixed point of read + write\n--- first ---\n" + resolved +
             "--- second ---\n" + again);
  }
  return {true, ""};
}

void require_finite(double value, std::string_view text, const char* what) {
  if (!std::isfinite(value)) {
    violated(std::string(what) + " accepted \"" + std::string(text) + "\" as the non-finite value " +
             std::to_string(value));
  }
}

}  // namespace

std::vector<std::string> overrides_in(std::string_view text) {
  static constexpr std::string_view kMarker = "#--set ";
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const auto line = text.substr(pos, end - pos);
    if (line.substr(0, kMarker.size()) == kMarker) out.emplace_back(line.substr(kMarker.size()));
    pos = end + 1;
  }
  return out;
}

SceneOutcome feed_scene(std::string_view text, const std::string& path) {
  SceneOutcome outcome;
  outcome.plain = scene_attempt(text, path, {});
  const auto overrides = overrides_in(text);
  if (!overrides.empty()) outcome.with_overrides = scene_attempt(text, path, overrides);
  return outcome;
}

Outcome feed_quantity(std::string_view text) {
  Outcome outcome;
  try {
    const Quantity q = parse_quantity(text);
    require_finite(q.value, text, "parse_quantity");
    outcome.accepted = true;
  } catch (const std::invalid_argument& e) {
    outcome.message = e.what();
    if (outcome.message.empty()) violated("parse_quantity rejected \"" + std::string(text) + "\" without a message");
  }
  // Every dimension a scene asks for (scene.cpp), so each unit-check branch is reached.
  static const Dimension kExpected[] = {
      dim::none,         dim::length,          dim::area,      dim::mass,  dim::time,
      dim::angle,        dim::density,         dim::pressure,  dim::force, dim::velocity,
      dim::acceleration, dim::energy_per_area, dim::viscosity, dim::rate,  Dimension{{0, 0, -1}, true}};
  for (const Dimension& d : kExpected) {
    try {
      const double v = parse_quantity_as(text, d);
      require_finite(v, text, "parse_quantity_as");
      if (!outcome.accepted)
        violated("parse_quantity_as accepted \"" + std::string(text) + "\" that parse_quantity rejects");
    } catch (const std::invalid_argument& e) {
      if (std::string(e.what()).empty()) violated("parse_quantity_as rejected without a message");
    }
  }
  try {
    const double metres = length_unit_in_metres(text);
    if (!(std::isfinite(metres) && metres > 0.0)) violated("length_unit_in_metres gave " + std::to_string(metres));
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).empty()) violated("length_unit_in_metres rejected without a message");
  }
  return outcome;
}

Outcome feed_snapshot_file(const std::string& path) {
  Snapshot s;
  try {
    s = read_snapshot(path);
  } catch (const InputError& e) {
    require_message_names(e.what(), path);
    return {false, e.what()};
  }
  for (const auto& f : s.fields) {
    if (f.components <= 0 || f.data.size() != s.point_count * static_cast<std::uint64_t>(f.components)) {
      violated("accepted snapshot field '" + f.name + "' has " + std::to_string(f.data.size()) + " values");
    }
  }
  // The format has one spelling per snapshot, so what was accepted must rewrite to its bytes; a
  // file of format 1 (FNV-1a checksum) rewrites to format 2, which must read back the same.
  const std::string copy = temporary_path(".rewrite.snap");
  write_snapshot(s, copy);
  const std::string original = file_bytes(path);
  std::uint32_t version = 0;
  std::memcpy(&version, original.data() + 8, sizeof version);  // accepted: the header is whole
  bool same = false;
  if (version == 1) {
    const Snapshot again = read_snapshot(copy);
    same = again.dimension == s.dimension && again.step == s.step && again.time == s.time &&
           again.point_count == s.point_count && again.fields.size() == s.fields.size();
    for (std::size_t k = 0; same && k < s.fields.size(); ++k)
      same = again.fields[k].name == s.fields[k].name && again.fields[k].components == s.fields[k].components &&
             again.fields[k].data == s.fields[k].data;
  } else {
    same = file_bytes(copy) == original;
  }
  std::remove(copy.c_str());
  if (!same) violated("an accepted snapshot does not rewrite to the same bytes (format 2) or contents (format 1)");
  return {true, ""};
}

Outcome feed_point_cloud_file(const std::string& path) {
  PointCloud cloud;
  try {
    cloud = read_point_cloud(path);
  } catch (const InputError& e) {
    require_message_names(e.what(), path);
    return {false, e.what()};
  }
  const std::size_t n = cloud.size();
  for (const auto* v : {&cloud.y, &cloud.z, &cloud.volume, &cloud.normal_x, &cloud.normal_y, &cloud.normal_z}) {
    if (v->size() != n) violated("accepted point cloud has arrays of different lengths");
  }
  if (cloud.region.size() != n || cloud.boundary_id.size() != n)
    violated("accepted point cloud has arrays of different lengths");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(cloud.volume[i] > 0.0 && std::isfinite(cloud.volume[i]))) violated("accepted point cloud has a bad volume");
    if (cloud.region[i] < 0 || static_cast<std::size_t>(cloud.region[i]) > cloud.boundaries.size())
      violated("accepted point cloud has a bad region");
  }
  // What was accepted must survive the writer and the reader unchanged (the solver and
  // restart rely on the points being exactly those the preprocessor wrote).
  const std::string copy = temporary_path(".rewrite.vtp");
  write_point_cloud(cloud, copy);
  PointCloud back;
  try {
    back = read_point_cloud(copy);
  } catch (const InputError& e) {
    std::remove(copy.c_str());
    violated(std::string("a rewritten accepted point cloud does not read back: ") + e.what());
  }
  std::remove(copy.c_str());
  bool same = back.dimension == cloud.dimension && back.spacing == cloud.spacing && back.horizon == cloud.horizon &&
              back.thickness == cloud.thickness && back.x == cloud.x && back.y == cloud.y && back.z == cloud.z &&
              back.volume == cloud.volume && back.region == cloud.region && back.boundary_id == cloud.boundary_id &&
              back.normal_x == cloud.normal_x && back.normal_y == cloud.normal_y && back.normal_z == cloud.normal_z &&
              back.precrack_vertices == cloud.precrack_vertices && back.boundaries.size() == cloud.boundaries.size();
  for (std::size_t k = 0; same && k < cloud.boundaries.size(); ++k) {
    const auto &a = cloud.boundaries[k], &b = back.boundaries[k];
    same = a.name == b.name && a.type == b.type && a.area == b.area && a.point_count == b.point_count;
  }
  if (!same) violated("an accepted point cloud changes through write_point_cloud + read_point_cloud");
  return {true, ""};
}

std::string write_temporary_input(std::string_view data, const std::string& extension) {
  const std::string path = temporary_path(extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  out.close();
  if (!out) violated("cannot write the fuzz input to " + path);
  return path;
}

}  // namespace mppm::fuzz
