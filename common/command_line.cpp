// Shared command-line handling and the exception -> exit-code mapping of every stage.
#include "common/command_line.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "common/input_error.hpp"

namespace mppm {

bool CommandLine::has_flag(const std::string& flag) const {
  return std::find(flags.begin(), flags.end(), flag) != flags.end();
}

std::optional<std::string> CommandLine::option(const std::string& name) const {
  if (auto it = options.find(name); it != options.end()) return it->second;
  return std::nullopt;
}

std::vector<std::string> CommandLine::all_values(const std::string& name) const {
  std::vector<std::string> values;
  for (const auto& [option_name, value] : option_values)
    if (option_name == name) values.push_back(value);
  return values;
}

CommandLine parse_command_line(int argc, char** argv, const CommandLineSpec& spec) {
  CommandLine cl;
  const auto takes_value = [&](const std::string& a) {
    return std::find(spec.value_options.begin(), spec.value_options.end(), a) != spec.value_options.end();
  };
  const auto is_flag = [&](const std::string& a) {
    return std::find(spec.flag_options.begin(), spec.flag_options.end(), a) != spec.flag_options.end();
  };
  for (int k = 1; k < argc; ++k) {
    std::string arg = argv[k];
    std::string inline_value;
    bool has_inline = false;
    if (arg.rfind("--", 0) == 0) {
      if (const auto eq = arg.find('='); eq != std::string::npos) {
        inline_value = arg.substr(eq + 1);
        arg = arg.substr(0, eq);
        has_inline = true;
      }
    }
    const auto next_value = [&]() -> std::string {
      if (has_inline) return inline_value;
      if (k + 1 >= argc) throw InputError(spec.program + ": option '" + arg + "' needs a value (see --help)");
      return argv[++k];
    };
    if (arg == "-h" || arg == "--help") {
      cl.help = true;
    } else if (arg == "--version") {
      cl.version = true;
    } else if (arg == "-q" || arg == "--quiet") {
      cl.quiet = true;
    } else if (arg == "--set") {
      cl.overrides.push_back(next_value());
    } else if (arg == "--threads" || arg == "-j") {
      const std::string v = next_value();
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || n < 1 || n > 4096) {
        throw InputError(spec.program + ": --threads " + v + ": expected a positive integer");
      }
      cl.threads = static_cast<int>(n);
    } else if (takes_value(arg)) {
      cl.options[arg] = next_value();
      cl.option_values.emplace_back(arg, cl.options[arg]);
    } else if (is_flag(arg)) {
      cl.flags.push_back(arg);
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw InputError(spec.program + ": unknown option '" + arg + "' (see --help)");
    } else {
      cl.positional.push_back(arg);
    }
  }
  return cl;
}

int run_stage(int argc, char** argv, const CommandLineSpec& spec, const std::function<int(const CommandLine&)>& body) {
  try {
    const CommandLine cl = parse_command_line(argc, argv, spec);
    if (cl.help) {
      std::cout << spec.usage;
      return kExitSuccess;
    }
    if (cl.version) {
      std::cout << spec.program << " (mppm) " << MPPM_VERSION << "\n";
      return kExitSuccess;
    }
    if (cl.threads) omp_set_num_threads(*cl.threads);
    return body(cl);
  } catch (const InputError& e) {
    std::cerr << spec.program << ": error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const NumericalFailure& e) {
    std::cerr << spec.program << ": numerical failure: " << e.what() << "\n";
    return kExitNumerical;
  } catch (const std::bad_alloc&) {
    std::cerr << spec.program << ": error: out of memory (try a coarser spacing or fewer output fields)\n";
    return kExitOther;
  } catch (const std::exception& e) {
    std::cerr << spec.program << ": internal error: " << e.what() << "\n";
    return kExitOther;
  }
}

}  // namespace mppm
