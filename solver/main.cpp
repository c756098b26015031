// mppm-solve: the thin main of the solver stage (everything is in mppm_solver).
#include "solver/solve_command.hpp"

int main(int argc, char** argv) { return mppm::solver::solve_command(argc, argv); }
