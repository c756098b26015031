// Running mppm-postprocess (and helper tools) from the postprocessor tests: exit code and
// captured output, without a shell quoting problem (arguments are quoted here).
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mppm::post::testing {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline CommandResult run_command(const std::vector<std::string>& argv) {
  static int counter = 0;
  const std::string log = (std::filesystem::temp_directory_path() /
                           ("mppm_post_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".log"))
                              .string();
  std::string command;
  for (const auto& a : argv) command += shell_quote(a) + " ";
  command += "> " + shell_quote(log) + " 2>&1";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  result.output = text.str();
  std::filesystem::remove(log);
  return result;
}

inline std::string postprocess_executable() { return std::string(MPPM_BINARY_DIR) + "/bin/mppm-postprocess"; }

// A fresh scratch directory under the build tree (kept after the test for inspection).
inline std::string scratch_directory(const std::string& name) {
  const auto dir = std::filesystem::path(MPPM_BINARY_DIR) / "test_scratch" / "postprocess" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace mppm::post::testing
