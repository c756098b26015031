// The wall time of the start-up of mppm-solve, phase by phase (run_info.json "start_up_seconds",
// the "start-up:" line of log.txt; docs/stages.md). The phases are contiguous: each one ends at a
// mark and the next one begins there, so that they add up to the whole start-up.
#pragma once
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace mppm::solver {

class PhaseTimer {
 public:
  using Clock = std::chrono::steady_clock;
  struct Phase {
    std::string name;  // for users: "read points", "bond families", ...
    double seconds;
  };

  // The first phase begins now.
  PhaseTimer() : start_(Clock::now()), last_(start_) {}

  // Ends the phase that began at the previous mark (or at the start), names it and returns the
  // time of the mark, where the next phase begins.
  Clock::time_point mark(std::string name) {
    const Clock::time_point now = Clock::now();
    phases_.push_back({std::move(name), std::chrono::duration<double>(now - last_).count()});
    last_ = now;
    return now;
  }

  Clock::time_point start() const { return start_; }
  const std::vector<Phase>& phases() const { return phases_; }
  // From the start to the last mark: the sum of the phases.
  double total_seconds() const { return std::chrono::duration<double>(last_ - start_).count(); }

 private:
  Clock::time_point start_, last_;
  std::vector<Phase> phases_;
};

}  // namespace mppm::solver
