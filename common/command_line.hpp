// The shared command-line contract of the three stages (docs/stages.md): positional arguments,
// `-o`, `--set key.path=value` (repeatable), `--threads N`, `--quiet`, `--help`, `--version`,
// plus stage-specific options declared by each main.
#pragma once
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mppm {

struct CommandLine {
  std::vector<std::string> positional;
  std::map<std::string, std::string> options;  // "--points" -> "pts.vtp", "-o" -> "run"
  std::vector<std::string> overrides;          // the --set values, in order
  std::vector<std::string> flags;              // "--force", "--figures" (no value)
  // Every value of every value option, in command-line order (for repeatable options; `options`
  // keeps the last value of each).
  std::vector<std::pair<std::string, std::string>> option_values;
  std::optional<int> threads;
  bool quiet = false;
  bool help = false;
  bool version = false;

  bool has_flag(const std::string& flag) const;
  std::optional<std::string> option(const std::string& name) const;
  // All values of a repeatable option, in command-line order.
  std::vector<std::string> all_values(const std::string& name) const;
};

struct CommandLineSpec {
  std::string program;                     // "mppm-solve"
  std::string usage;                       // full --help text
  std::vector<std::string> value_options;  // options taking a value, e.g. {"-o", "--points"}
  std::vector<std::string> flag_options;   // options without a value, e.g. {"--force"}
};

// Parses argv; throws InputError ("mppm-solve: unknown option '--foo' (see --help)").
CommandLine parse_command_line(int argc, char** argv, const CommandLineSpec& spec);

// Runs a stage's body with the shared behaviour: --help/--version, thread count, and the
// mapping of exceptions to exit codes (InputError -> 2, NumericalFailure -> 3, other -> 1),
// with the message on stderr prefixed by the program name.
int run_stage(int argc, char** argv, const CommandLineSpec& spec, const std::function<int(const CommandLine&)>& body);

}  // namespace mppm
