// Errors that the user can fix (bad scene, geometry, points file, run directory).
// Every stage maps InputError to exit code 2 and NumericalFailure to exit code 3.
#pragma once
#include <stdexcept>
#include <string>

namespace mppm {

// Bad input. The message already names the file (and line, key) and what was expected.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A numerical failure detected during a run (non-finite values, unexplained energy growth).
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Exit codes of docs/stages.md.
inline constexpr int kExitSuccess = 0;
inline constexpr int kExitOther = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitNumerical = 3;

}  // namespace mppm
