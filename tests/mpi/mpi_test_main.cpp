// The main of the mpi-labelled tests (tests/mpi.cmake): MPI for the whole run; every process runs
// every test, the first prints them all, the others only their failures, and a failure on any
// process fails the run (mpirun returns a nonzero exit code).
#include <gtest/gtest.h>

#include "solver/process_group.hpp"

int main(int argc, char** argv) {
  mppm::solver::MpiSession mpi(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (mppm::solver::ProcessGroup::world().rank() != 0) GTEST_FLAG_SET(brief, true);
  return RUN_ALL_TESTS();
}
