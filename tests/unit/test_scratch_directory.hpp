// A scratch directory per test process and prefix (CTest runs a suite's tests as parallel
// processes), removed at the end unless a test failed (kept for a look): a test file registers
// RemoveScratch(prefix) as a global test environment and makes its directories with
// fresh_scratch_directory(prefix, name).
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>

namespace mppm::testing {

inline std::filesystem::path scratch_root(const std::string& prefix) {
  return std::filesystem::path(MPPM_BINARY_DIR) / "test_scratch" / (prefix + "_" + std::to_string(::getpid()));
}

// Registers the removal of the prefix's scratch root at the end of the test program.
class RemoveScratch : public ::testing::Environment {
 public:
  explicit RemoveScratch(std::string prefix) : prefix_(std::move(prefix)) {}
  void TearDown() override {
    if (::testing::UnitTest::GetInstance()->Passed()) std::filesystem::remove_all(scratch_root(prefix_));
  }

 private:
  std::string prefix_;
};

// An empty directory `name` under the prefix's scratch root.
inline std::string fresh_scratch_directory(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir = scratch_root(prefix) / name;
  std::filesystem::remove_all(dir);
  return dir.string();
}

}  // namespace mppm::testing
