// A quiescent gas at uniform pressure over a strongly non-uniform porosity field (a packed
// layer with sharp edges plus random cells) on a stretched grid stays exactly at rest: the
// well-balanced a grad p term (stage_update.hpp) gives L(U) = 0 to the last bit, and a cell
// whose state did not change keeps its primitives. With skipping on, such a gas costs nothing.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "verification/gas_test_support.hpp"

using namespace dustlift;

namespace {

void run_quiescent(GasConfig cfg, double p0, double T0, bool skip) {
  cfg.skip_resting_cells = skip;
  AxisSpec x, y;
  x.start = -0.02;
  x.end = 0.05;
  x.cell_size = 1e-3;
  x.uniform_start = 0.0;
  x.uniform_end = 0.04;
  x.cells_below = 8;
  x.cells_above = 4;
  y.start = 0.0;
  y.end = 0.03;
  y.cell_size = 1e-3;
  y.uniform_start = 0.0;
  y.uniform_end = 0.02;
  y.cells_above = 5;
  const Grid2D grid(x, y, 2);
  GasSolver gas(grid, cfg);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> porosity(0.3, 1.0);
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i)
      gas.porosity()(i, j) = j < 4 ? 0.41 : (i % 3 == 0 ? porosity(rng) : 1.0);
  InitialCondition ic;
  ic.state = {p0 / (cfg.thermo.gas_constant * T0), 0.0, 0.0, p0};
  gas.initialize(ic);
  for (int n = 0; n < 200; ++n) gas.step(gas.stable_dt());
  double max_speed = 0.0, max_dp = 0.0;
  const GasPrimitives s = gas.primitives();
  for (int j = 0; j < grid.ny(); ++j) {
    for (int i = 0; i < grid.nx(); ++i) {
      max_speed = std::max({max_speed, std::abs((*s.u)(i, j)), std::abs((*s.v)(i, j))});
      max_dp = std::max(max_dp, std::abs((*s.p)(i, j) - p0) / p0);
    }
  }
  const double c = gas.sound_speed(0, 0);
  std::printf("quiescent over porosity 0.3..1 (skip %s): max |u|/c = %.3e, max |dp|/p = %.3e after 200 steps, "
              "%lld cell-stage updates\n",
              skip ? "on" : "off", max_speed / c, max_dp, gas.cell_updates());
  EXPECT_EQ(max_speed, 0.0);
  EXPECT_EQ(max_dp, 0.0);
  if (skip) {
    EXPECT_EQ(gas.cell_updates(), 0) << "a gas at rest everywhere needs no update";
  } else {
    EXPECT_EQ(gas.cell_updates(), 200LL * 3 * grid.interior_cells());
  }
}

}  // namespace

TEST(QuiescentPorosity, ThermallyPerfectViscousWalls) {
  GasConfig cfg;  // NASA air, Gordon-Wilke transport
  cfg.boundary.left = BoundaryKind::SlipWall;
  cfg.boundary.right = BoundaryKind::Outflow;
  cfg.boundary.bottom = BoundaryKind::NoSlipWall;
  cfg.boundary.top = BoundaryKind::SlipWall;
  run_quiescent(cfg, 101000.0, 300.0, false);
  run_quiescent(cfg, 101000.0, 300.0, true);
}

TEST(QuiescentPorosity, CaloricallyPerfectInviscidInflowOutflow) {
  GasConfig cfg;
  cfg.thermo.model = ThermoModel::CaloricallyPerfect;
  cfg.transport.model = TransportModel::Inviscid;
  cfg.scheme.limiter = Limiter::VanAlbada;
  cfg.boundary.left = BoundaryKind::Inflow;
  cfg.boundary.right = BoundaryKind::Outflow;
  run_quiescent(cfg, 101000.0, 300.0, false);
}
