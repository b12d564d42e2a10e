// DEM throughput on the reference setup (docs/dem.md, "Benchmark"):
// 60,000 parcels of 100 um (rho 980, areal fraction 0.589) filling a box 400 mm x 2 mm,
// periodic in x, walls at y = 0 and 2 mm, every parcel at 1 m/s in a random direction;
// k_n = 5e4 N/m, k_t = 2/7 k_n, Coulomb friction 0.5, normal restitution 0.9,
// dt = 0.1 sqrt(m/k_n); 20,000 timed steps (DUSTLIFT_BENCH_STEPS overrides, for profiling).
// Counters: particle-steps per second (wall clock) and per CPU second, 1 and 2 threads.
//   cmake --build build/release --target bench_dem_layer
//   ./build/release/bench/bench_dem_layer --benchmark_repetitions=3
// (Threads wait as in the dustlift program: solver/core/wait_policy.hpp; see main.)
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <cstdlib>
#include <ctime>

#include "bench/dem_reference_layer.hpp"
#include "bench/run_benchmarks.hpp"
#include "solver/dem/parcel_system.hpp"

using namespace dustlift;

namespace {

ParcelSystem reference_setup() {
  return reference_layer(true);
}

/// CPU seconds used by this process (all threads).
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int timed_steps() {
  const char* env = std::getenv("DUSTLIFT_BENCH_STEPS");
  return env != nullptr ? std::atoi(env) : 20000;
}

void BM_DemReferenceLayer(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  const int steps = timed_steps();
  long long particle_steps = 0;
  double cpu_seconds = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    ParcelSystem s = reference_setup();
    const double dt = s.stable_time_step();
    s.step(dt);  // first neighbour build outside the timing
    state.ResumeTiming();
    const double cpu0 = process_cpu_seconds();
    for (int n = 0; n < steps; ++n) s.step(dt);
    cpu_seconds += process_cpu_seconds() - cpu0;
    particle_steps += static_cast<long long>(s.size()) * steps;
    state.counters["parcels"] = static_cast<double>(s.size());
    state.counters["rebuilds"] = static_cast<double>(s.neighbour_rebuilds());
    state.counters["contacts_end"] = static_cast<double>(s.contact_pair_count());
    state.counters["list_slots_per_parcel"] =
        static_cast<double>(s.nbr_index.size()) / static_cast<double>(s.size());
  }
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(static_cast<double>(particle_steps), benchmark::Counter::kIsRate);
  // Per core: particle-steps per CPU second of all threads (robust on a shared machine,
  // where wall time also counts the time other jobs hold our cores).
  state.counters["per_cpu_s"] = static_cast<double>(particle_steps) / cpu_seconds;
}

}  // namespace

BENCHMARK(BM_DemReferenceLayer)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

int main(int argc, char** argv) {
  return dustlift::bench::run_benchmarks(argc, argv);
}
