#include "solver/app/layout_advice.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace dustlift {

LayoutAdvice recommend_layout(const LayoutFacts& facts) {
  LayoutAdvice a;
  a.ranks = 1;
  a.threads = std::max(1, facts.cores);
  a.command = fmt::format("dustlift run SCENE -t {}", a.threads);
  if (a.threads == 1) {
    a.reason = "one core: nothing to split";
  } else if (!facts.built_with_mpi) {
    a.reason = "this build has no MPI, and threads are the faster layout on one machine anyway";
  } else if (facts.periodic_with_particles) {
    a.reason = "a periodic channel with particles runs on one rank";
  } else {
    a.reason = fmt::format(
        "on one machine threads ran every scene of cases/ at least as fast as {} MPI ranks "
        "(docs/parallel.md, \"Which layout\"); ranks are for more cores than one machine has: "
        "mpirun -np MACHINES --map-by ppr:1:node --bind-to none dustlift run SCENE -t "
        "CORES_PER_MACHINE",
        a.threads);
  }
  return a;
}

}  // namespace dustlift
