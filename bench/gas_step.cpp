// Cost of one SSP-RK3 gas step on a 400 x 160 cell piece of the paper's problem
// (Ms = 1.44 shock in thermally perfect air, Gordon-Wilke viscosity, MUSCL-3 + SLAU2,
// 0.25 mm cells, a non-uniform porosity layer). Reports ns per cell per RK stage.
// Run: build/release/bench/bench_gas_step
#include <benchmark/benchmark.h>
#include <omp.h>

#include "bench/run_benchmarks.hpp"
#include "solver/gas/gas_solver.hpp"

using namespace dustlift;

namespace {

GasSolver make_shock_problem(TransportModel transport, ThermoModel thermo) {
  AxisSpec x, y;
  x.start = 0.0;
  x.end = 0.1;
  x.cells = 400;
  y.start = 0.0;
  y.end = 0.04;
  y.cells = 160;
  const Grid2D grid(x, y, 2);
  GasConfig cfg;
  cfg.thermo.model = thermo;
  cfg.transport.model = transport;
  cfg.boundary.left = BoundaryKind::Inflow;
  cfg.boundary.right = BoundaryKind::Outflow;
  cfg.boundary.bottom = BoundaryKind::NoSlipWall;
  cfg.boundary.top = BoundaryKind::SlipWall;
  GasSolver gas(grid, cfg);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 400; ++i) gas.porosity()(i, j) = 0.41;  // a 2 mm packed layer
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Shock;
  ic.state = {101000.0 / (288.19 * 300.0), 0.0, 0.0, 101000.0};
  ic.mach = 1.44;
  ic.position = 0.03;
  gas.initialize(ic);
  for (int n = 0; n < 20; ++n) gas.step(gas.stable_dt());  // develop the shock structure
  return gas;
}

void run_steps(benchmark::State& state, TransportModel transport, ThermoModel thermo) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  GasSolver gas = make_shock_problem(transport, thermo);
  const double dt = gas.stable_dt();
  for (auto _ : state) gas.step(dt);
  const double cell_stages = 3.0 * static_cast<double>(gas.grid().interior_cells());
  // Seconds per cell per stage (printed with an SI prefix, e.g. "150n" = 150 ns).
  state.counters["time_per_cell_stage"] = benchmark::Counter(
      cell_stages * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_GasStepViscousThermallyPerfect(benchmark::State& s) {
  run_steps(s, TransportModel::GordonWilke, ThermoModel::ThermallyPerfect);
}
void BM_GasStepInviscidThermallyPerfect(benchmark::State& s) {
  run_steps(s, TransportModel::Inviscid, ThermoModel::ThermallyPerfect);
}
void BM_GasStepInviscidCaloricallyPerfect(benchmark::State& s) {
  run_steps(s, TransportModel::Inviscid, ThermoModel::CaloricallyPerfect);
}

/// The paper's grid (section 3.1 as read in docs/dem.md): 0.25 mm cells on
/// [0, 400 mm] x [0, 32 mm], 300 stretched cells upstream and 32 above: 1900 x 160 cells.
void BM_GasStepPaperGrid(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  const bool skip = state.range(1) != 0;  // exact skipping of resting cells
  AxisSpec x, y;
  x.start = -0.5;
  x.end = 0.4;
  x.cell_size = 0.25e-3;
  x.uniform_start = 0.0;
  x.uniform_end = 0.4;
  x.cells_below = 300;
  y.start = 0.0;
  y.end = 0.1;
  y.cell_size = 0.25e-3;
  y.uniform_start = 0.0;
  y.uniform_end = 0.032;
  y.cells_above = 32;
  const Grid2D grid(x, y, 2);
  GasConfig cfg;  // NASA air, Gordon-Wilke, MUSCL-3 minmod
  cfg.boundary.left = BoundaryKind::Inflow;
  cfg.boundary.right = BoundaryKind::Outflow;
  cfg.boundary.bottom = BoundaryKind::NoSlipWall;
  cfg.boundary.top = BoundaryKind::SlipWall;
  cfg.skip_resting_cells = skip;
  GasSolver gas(grid, cfg);
  for (int j = 0; j < 8; ++j)
    for (int i = 300; i < grid.nx(); ++i) gas.porosity()(i, j) = 0.41;
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Shock;
  ic.state = {101000.0 / (288.19 * 300.0), 0.0, 0.0, 101000.0};
  ic.mach = 1.44;
  ic.position = -0.01;
  gas.initialize(ic);
  const double dt = gas.stable_dt();
  const long long updates0 = gas.cell_updates();
  for (auto _ : state) gas.step(dt);
  state.counters["time_per_cell_stage"] =
      benchmark::Counter(3.0 * static_cast<double>(grid.interior_cells()) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  // Cell-stage updates per second counted over the full grid, and the share actually computed.
  state.counters["cell_stages_per_s"] =
      benchmark::Counter(3.0 * static_cast<double>(grid.interior_cells()) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
  state.counters["computed_share"] = static_cast<double>(gas.cell_updates() - updates0) /
                                     (3.0 * static_cast<double>(grid.interior_cells()) * static_cast<double>(state.iterations()));
  state.counters["dt_s"] = dt;
}

}  // namespace

// {threads, skip}: without skipping every cell is computed (the raw throughput).
BENCHMARK(BM_GasStepPaperGrid)->Args({1, 0})->Args({2, 0})->Args({1, 1})->Args({2, 1})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GasStepViscousThermallyPerfect)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GasStepInviscidThermallyPerfect)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GasStepInviscidCaloricallyPerfect)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

int main(int argc, char** argv) { return dustlift::bench::run_benchmarks(argc, argv); }
