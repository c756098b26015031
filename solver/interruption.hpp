// Ctrl-C (SIGINT) and SIGTERM during a run: the run loop finishes its step, writes a snapshot of
// the (good) current state, marks run_info.json "interrupted" and returns, instead of dying with
// half the tables unwritten.
#pragma once

namespace mppm::solver {

// Installs the handlers for the lifetime of the object and restores the previous ones after.
class InterruptionHandlers {
 public:
  InterruptionHandlers();
  ~InterruptionHandlers();
  InterruptionHandlers(const InterruptionHandlers&) = delete;
  InterruptionHandlers& operator=(const InterruptionHandlers&) = delete;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

void request_interruption();  // what the handlers do (async-signal-safe); tests call it too
bool interruption_requested();
void clear_interruption();

}  // namespace mppm::solver
