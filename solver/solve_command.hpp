// The mppm-solve command line (docs/stages.md) as a library function, so that tests can check its
// exit codes and messages without starting a process.
#pragma once

namespace mppm::solver {

// mppm-solve SCENE --points POINTS.vtp -o RUN_DIR [--set k=v] [--threads N] [--quiet] [--force]
// Returns the exit code: 0 success, 2 bad input, 3 numerical failure, 1 other.
int solve_command(int argc, char** argv);

}  // namespace mppm::solver
