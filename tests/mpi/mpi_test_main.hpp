#pragma once
// main() of the MPI suites (ctest runs each under `mpirun -np 2`): every rank runs every
// test, only rank 0 prints, and a failure on any rank fails the run (and mpirun's exit code).
#include <gtest/gtest.h>

#include "solver/parallel/world.hpp"

namespace dustlift {

inline int run_tests_on_every_rank(int argc, char** argv) {
  const ParallelSession mpi(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  const auto world = make_world_communicator();
  if (world->rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int result = RUN_ALL_TESTS();
  return world->any(result != 0) ? 1 : 0;
}

}  // namespace dustlift
