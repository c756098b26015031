// Failures of a distributed run agreed by all its processes (docs/theory.md section 13). A process
// that fails alone would leave the others waiting for it in the next exchange or sum: so every
// step of a run that can fail on one process (a file that cannot be written, a refusal of one
// process's share) runs through run_agreed, after which either every process goes on or every
// process throws the same exception, that of the lowest failing process (its kind: bad input,
// numerical failure or other, and its message). Only the first process prints it.
#pragma once
#include <exception>
#include <functional>

#include "solver/process_group.hpp"

namespace mppm::solver {

// Collective. Runs `step` on this process; when it throws on any process, every process throws
// the lowest failing process's failure. On one process: `step` as it is, nothing caught.
void run_agreed(const ProcessGroup& group, const std::function<void()>& step);

// True when `failure` (caught at the top of mppm-solve) was thrown by run_agreed on every process:
// the others are not waiting for this one, which may finish normally. A failure that was not agreed
// (an internal error on one process) must end the whole run instead (MPI_Abort), never hang it.
bool failure_was_agreed(const std::exception_ptr& failure);

}  // namespace mppm::solver
