// Interruption flag set from signal handlers.
#include "solver/interruption.hpp"

#include <csignal>

namespace mppm::solver {

namespace {
volatile std::sig_atomic_t interrupted = 0;
extern "C" void on_signal(int) { interrupted = 1; }
}  // namespace

void request_interruption() { interrupted = 1; }
bool interruption_requested() { return interrupted != 0; }
void clear_interruption() { interrupted = 0; }

InterruptionHandlers::InterruptionHandlers()
    : previous_int_(std::signal(SIGINT, on_signal)), previous_term_(std::signal(SIGTERM, on_signal)) {}

InterruptionHandlers::~InterruptionHandlers() {
  std::signal(SIGINT, previous_int_ == SIG_ERR ? SIG_DFL : previous_int_);
  std::signal(SIGTERM, previous_term_ == SIG_ERR ? SIG_DFL : previous_term_);
}

}  // namespace mppm::solver
