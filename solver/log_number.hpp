// Numbers in the run's log lines and messages: six significant digits, the form every log line uses.
#pragma once
#include <sstream>
#include <string>

namespace mppm::solver {

inline std::string log_number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace mppm::solver
