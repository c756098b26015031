// Replays every file of the fuzz corpus (tests/fuzz/corpus/) and every crash reproducer the
// fuzzers found (tests/fuzz/crashes/) through the fuzzers' own entry points, in the normal
// build: a malformed input must be rejected with an InputError (std::invalid_argument for a
// bare unit string) whose message names the file and the problem; nothing else may escape.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <typeinfo>

#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "tests/fuzz/fuzz_entry_points.hpp"

namespace fs = std::filesystem;
using namespace mppm;

namespace {

const fs::path kFuzzDir = fs::path(MPPM_SOURCE_DIR) / "tests" / "fuzz";

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// expected_errors.txt: "<dir>/<target>/<file> | <fragment the message must contain>".
std::map<std::string, std::string> expected_errors() {
  std::map<std::string, std::string> out;
  std::ifstream in(kFuzzDir / "expected_errors.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto bar = line.find(" | ");
    if (bar == std::string::npos) {
      ADD_FAILURE() << "expected_errors.txt: line without ' | ': " << line;
      continue;
    }
    out[line.substr(0, bar)] = line.substr(bar + 3);
  }
  return out;
}

// Every input of a target: the seed corpus and the crash reproducers, by their key in
// expected_errors.txt ("corpus/scene/bad_x.yaml").
std::vector<std::string> inputs_of(const std::string& target) {
  std::vector<std::string> keys;
  for (const char* dir : {"corpus", "crashes"}) {
    const fs::path folder = kFuzzDir / dir / target;
    if (!fs::is_directory(folder)) continue;
    for (const auto& entry : fs::directory_iterator(folder)) {
      if (entry.is_regular_file())
        keys.push_back(std::string(dir) + "/" + target + "/" + entry.path().filename().string());
    }
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

fuzz::Outcome feed(const std::string& target, const fs::path& path) {
  if (target == "scene") return fuzz::feed_scene(file_text(path), path.string()).final();
  if (target == "quantity") return fuzz::feed_quantity(file_text(path));
  if (target == "snapshot") return fuzz::feed_snapshot_file(path.string());
  return fuzz::feed_point_cloud_file(path.string());
}

class CorpusReplay : public ::testing::TestWithParam<std::string> {};

TEST_P(CorpusReplay, EveryInputIsAcceptedOrRejectedWithAMessageNamingTheProblem) {
  const std::string target = GetParam();
  const auto expected = expected_errors();
  const auto keys = inputs_of(target);
  ASSERT_GE(keys.size(), 5u) << "the " << target << " corpus is missing or nearly empty";
  int valid = 0, bad = 0;
  for (const auto& key : keys) {
    SCOPED_TRACE(key);
    const fs::path path = kFuzzDir / key;
    const std::string name = path.filename().string();
    fuzz::Outcome outcome;
    try {
      outcome = feed(target, path);
    } catch (const fuzz::ContractViolation& e) {
      ADD_FAILURE() << "contract violated: " << e.what();
      continue;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "escaped as " << typeid(e).name() << " instead of an input error: " << e.what();
      continue;
    }
    if (name.rfind("valid_", 0) == 0) {
      ++valid;
      EXPECT_TRUE(outcome.accepted) << "a valid seed was rejected: " << outcome.message;
    } else if (name.rfind("bad_", 0) == 0) {
      ++bad;
      EXPECT_FALSE(outcome.accepted) << "a malformed seed was accepted";
      const auto it = expected.find(key);
      if (it == expected.end()) {
        ADD_FAILURE() << "no line for it in expected_errors.txt (what must its message say?); it said: "
                      << outcome.message;
        continue;
      }
      EXPECT_NE(outcome.message.find(it->second), std::string::npos)
          << "the message does not name the problem '" << it->second << "': " << outcome.message;
      // Files must be named in the message (the entry point already checks it; the unit
      // parser sees no file, its caller adds the key and file: see the test below).
      if (target != "quantity") {
        EXPECT_TRUE(outcome.message.find(path.string()) != std::string::npos || outcome.message.rfind("--set ", 0) == 0)
            << outcome.message;
      }
    }
  }
  // Both kinds must be present, or the checks above prove nothing about this target.
  EXPECT_GE(valid, 1);
  EXPECT_GE(bad, 3);
}

std::string target_name(const ::testing::TestParamInfo<std::string>& target) { return target.param; }

INSTANTIATE_TEST_SUITE_P(FuzzTargets, CorpusReplay,
                         ::testing::Values(std::string("scene"), std::string("quantity"), std::string("snapshot"),
                                           std::string("point_cloud")),
                         target_name);

TEST(CorpusExpectations, EveryLineNamesAnExistingMalformedInput) {
  for (const auto& [key, fragment] : expected_errors()) {
    SCOPED_TRACE(key);
    EXPECT_TRUE(fs::is_regular_file(kFuzzDir / key)) << "stale line in expected_errors.txt";
    EXPECT_EQ(fs::path(key).filename().string().rfind("bad_", 0), 0u) << "only bad_* inputs have an expected error";
    EXPECT_FALSE(fragment.empty());
  }
}

// A rejected unit string inside a scene becomes an InputError that names the file, the line
// and the key (what a user sees), not only the unit parser's message.
TEST(CorpusExpectations, MalformedQuantitiesInASceneNameFileLineAndKey) {
  const std::string path = "/cases/reliability/scene.yaml";
  const std::string head =
      "mppm: 1\ndimension: 2\nthickness: 1 mm\n"
      "geometry: {file: plate.geo, spacing: 1 mm, horizon_factor: 3}\n"
      "material:\n  density: 2000\n  lambda: 1 GPa\n  mu: ";
  const std::string tail = "\ntime: {end: 1 us}\n";
  int checked = 0;
  for (const auto& key : inputs_of("quantity")) {
    if (fs::path(key).filename().string().rfind("bad_", 0) != 0) continue;
    SCOPED_TRACE(key);
    // As a YAML double-quoted string, so any byte reaches the unit parser unchanged.
    std::string quoted = "\"";
    for (unsigned char c : file_text(kFuzzDir / key)) {
      static const char* hex = "0123456789abcdef";
      if (c == '"' || c == '\\')
        quoted += std::string("\\") + static_cast<char>(c);
      else if (c >= 0x20 && c < 0x7f)
        quoted += static_cast<char>(c);
      else
        quoted += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    }
    quoted += "\"";
    try {
      parse_scene(head + quoted + tail, path);
      ADD_FAILURE() << "accepted mu: " << quoted;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ":8: material.mu: "), std::string::npos) << e.what();
    }
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

}  // namespace
