// Hard case for the porosity treatment: the paper's Ms = 1.44 shock running over a packed
// layer (alpha_g = 0.41 with a sharp jump at its top, a random-porosity top row and a blunt
// leading edge) on a no-slip floor with Gordon-Wilke viscosity. The run must stay positive
// (no NumericalFailure), push gas into the layer, and leave the flow far above the layer
// close to the 1-D post-shock state.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "solver/gas/gas_solver.hpp"
#include "solver/gas/shock_relations.hpp"

using namespace dustlift;

TEST(GasStress, ShockOverPackedPorousLayer) {
  AxisSpec x, y;
  x.start = 0.0;
  x.end = 0.04;
  x.cells = 160;
  y.start = 0.0;
  y.end = 0.01;
  y.cells = 40;
  const Grid2D grid(x, y, 2);
  GasConfig cfg;  // NASA air + Gordon-Wilke, MUSCL-3 minmod
  cfg.boundary.left = BoundaryKind::Inflow;
  cfg.boundary.right = BoundaryKind::Outflow;
  cfg.boundary.bottom = BoundaryKind::NoSlipWall;
  cfg.boundary.top = BoundaryKind::SlipWall;
  GasSolver gas(grid, cfg);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ragged(0.41, 1.0);
  for (int i = 0; i < grid.nx(); ++i) {
    if (grid.x().center(i) < 0.01) continue;  // layer starts 10 mm downstream
    for (int j = 0; j < 8; ++j) gas.porosity()(i, j) = 0.41;  // 2 mm deep
    gas.porosity()(i, 8) = ragged(rng);
  }
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Shock;
  ic.state = {101000.0 / (288.19 * 300.0), 0.0, 0.0, 101000.0};
  ic.mach = 1.44;
  ic.position = 0.005;
  gas.initialize(ic);
  const ShockJump jump = normal_shock(ic.state, ic.mach, cfg.thermo, 'x');
  // Shock travels 25 mm: over 15 mm of layer.
  const double end_time = 0.025 / jump.shock_speed;
  double t = 0.0;
  int steps = 0;
  ASSERT_NO_THROW({
    while (t < end_time) {
      const double dt = std::min(gas.stable_dt(), end_time - t);
      gas.step(dt);
      t += dt;
      ++steps;
    }
  });
  const GasPrimitives s = gas.primitives();
  // Far above the layer and behind the shock the flow is close to the 1-D post-shock state
  // (measured +1.6 %: the wave reflected from the layer's leading edge).
  const int i_behind = grid.x().locate(0.02), j_top = grid.ny() - 2;
  EXPECT_NEAR((*s.p)(i_behind, j_top), jump.post.p, 0.03 * jump.post.p);
  // Gas was pushed into the layer: its pressure rose everywhere the shock has passed.
  EXPECT_GT((*s.p)(grid.x().locate(0.015), 2), 1.5 * ic.state.p);
  // Everything stays finite and positive (NumericalFailure would have thrown).
  double min_rho = 1e300;
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) min_rho = std::min(min_rho, (*s.rho)(i, j));
  EXPECT_GT(min_rho, 0.5 * ic.state.rho);
  std::printf("shock over porous layer: %d steps, min rho %.4f, p above layer %.0f Pa (1-D %.0f)\n", steps, min_rho,
              (*s.p)(i_behind, j_top), jump.post.p);
}
