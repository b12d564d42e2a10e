// Cost of the particle code in a gas-only scene ("a gas-only scene with the particle
// code compiled in runs within 5 % of the time of the same scene before coupling existed").
// Before coupling, a step was GasSolver::stable_dt() + GasSolver::step(); now it is
// Simulation::advance(), which must add nothing measurable when the scene has no particles.
// Run: ./build/release/bench/bench_gas_only_overhead --benchmark_repetitions=9
//      --benchmark_report_aggregates_only=true   (compare the medians)
#include <benchmark/benchmark.h>

#include "bench/run_benchmarks.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/sim/simulation.hpp"

namespace {

using namespace dustlift;

/// The paper's gas problem on a 400 x 160 part of its grid: a Mach 1.44 shock, viscous,
/// thermally perfect air; no particles.
Scene gas_only_scene() {
  return parse_scene(R"(
[run]
end_time = 1.0
[grid]
x = { start = -0.02, end = 0.08, cells = 400 }
y = { start = -0.002, end = 0.038, cells = 160 }
[boundary]
left = "inflow"
right = "outflow"
bottom = "no_slip_wall"
top = "no_slip_wall"
[initial]
kind = "shock"
mach = 1.44
position = 0.0
state = { p = 101.0e3, T = 300.0 }
)",
                     "gas_only.toml");
}

void BM_GasStepBeforeCoupling(benchmark::State& state) {
  const Scene scene = gas_only_scene();
  const Grid2D grid(scene.grid.x, scene.grid.y, kGhostLayers);
  GasSolver gas(grid, scene.gas);
  gas.initialize(scene.initial);
  for (auto _ : state) {
    const double dt = gas.stable_dt();
    gas.step(dt);
    benchmark::DoNotOptimize(dt);
  }
  state.counters["cells"] = static_cast<double>(grid.interior_cells());
}
BENCHMARK(BM_GasStepBeforeCoupling)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SimulationAdvanceGasOnly(benchmark::State& state) {
  Simulation sim(gas_only_scene());
  for (auto _ : state) benchmark::DoNotOptimize(sim.advance(1.0));
  state.counters["cells"] = static_cast<double>(sim.grid().interior_cells());
}
BENCHMARK(BM_SimulationAdvanceGasOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  return dustlift::bench::run_benchmarks(argc, argv);
}
