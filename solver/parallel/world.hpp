#pragma once
// The program's ranks: MPI started for the life of the program, and the world communicator
// (world.cpp without MPI, mpi/world_mpi.cpp with it).
#include <memory>

#include "solver/core/communicator.hpp"

namespace dustlift {

/// MPI for the life of the program (MPI_Init_thread with MPI_THREAD_FUNNELED: OpenMP
/// threads inside a rank, MPI calls from its main thread only); nothing without MPI.
class ParallelSession {
 public:
  ParallelSession(int& argc, char**& argv);
  ~ParallelSession();
  ParallelSession(const ParallelSession&) = delete;
  ParallelSession& operator=(const ParallelSession&) = delete;

 private:
  bool started_ = false;  ///< this session called MPI_Init_thread (and so finalizes)
};

/// The ranks the program was started on (MPI_COMM_WORLD; one rank without MPI or before a
/// ParallelSession).
std::unique_ptr<Communicator> make_world_communicator();

/// Whether this build has MPI (the CLI reports it in `dustlift info`).
bool built_with_mpi();

}  // namespace dustlift
