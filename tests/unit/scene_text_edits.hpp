// Helpers of the scene tests: the error a scene text is refused with, and a scene text with one
// passage replaced.
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "common/scene.hpp"

namespace mppm::testing {

// The message of the InputError that parsing `text` (as the file `path`) throws; "" if it parses.
inline std::string scene_error_of(const std::string& text, const std::string& path,
                                  const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, path, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// `text` with the first `from` replaced by `to` (a test failure if `from` is not in it).
inline std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

}  // namespace mppm::testing
