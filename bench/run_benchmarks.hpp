#pragma once
// The main of every Google Benchmark executable here: threads wait as in the dustlift
// program (solver/core/wait_policy.hpp; libgomp reads the policy before main, hence the
// restart), so that benchmark rates compare with those of real runs.
#include <benchmark/benchmark.h>

#include "solver/core/wait_policy.hpp"

namespace dustlift::bench {

inline int run_benchmarks(int argc, char** argv) {
  reexec_with_default_wait_policy(argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace dustlift::bench
