#include "solver/parallel/world.hpp"

// Without MPI the world is this one process (the MPI build compiles mpi/world_mpi.cpp instead).
#ifndef DUSTLIFT_HAS_MPI
namespace dustlift {
ParallelSession::ParallelSession(int&, char**&) {}
ParallelSession::~ParallelSession() = default;
std::unique_ptr<Communicator> make_world_communicator() {
  return std::make_unique<SingleRank>();
}
bool built_with_mpi() {
  return false;
}
}  // namespace dustlift
#endif
