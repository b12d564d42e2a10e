#pragma once
// `dustlift info`'s advice on how to lay a run out over this machine's cores: ranks, threads
// per rank, and why (docs/parallel.md, "Which layout").
#include <string>

namespace dustlift {

/// What the advice depends on.
struct LayoutFacts {
  int cores = 1;                         ///< threads `dustlift run` takes by default
  bool built_with_mpi = false;           ///< mpirun can split the grid into slabs
  bool periodic_with_particles = false;  ///< such a scene runs on one rank only
};

struct LayoutAdvice {
  int ranks = 1;
  int threads = 1;      ///< per rank
  std::string command;  ///< how to start it, SCENE standing for the scene file
  std::string reason;   ///< one sentence: why this layout
};

/// On one machine: one rank with a thread per core. Threads ran every scene of cases/ at least
/// as fast as as many MPI ranks on the machine measured (docs/parallel.md): ranks pay for
/// halos, gathers for the observers and waits at every collective, threads share the memory.
/// Ranks are for more cores than one machine has (a rank per machine, threads inside it).
LayoutAdvice recommend_layout(const LayoutFacts& facts);

}  // namespace dustlift
