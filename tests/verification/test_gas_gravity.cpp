// Gravity on the gas (gas.gravity = [g_x, g_y]): a uniform gas in a doubly periodic box
// falls freely, u = g t, with its density and internal energy unchanged, the momentum
// total M g t and the energy total E0 + M |g t|^2 / 2 (SSP-RK3 integrates du/dt = g
// exactly); no cell is skipped as resting under gravity; the scene key parses and is
// refused when it is not two numbers.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"
#include "verification/gas_test_support.hpp"

using namespace dustlift;
using namespace dustlift::gas_test;

namespace {

GasConfig periodic_air_with_gravity(double gx, double gy) {
  GasConfig c;
  c.thermo.model = ThermoModel::ThermallyPerfect;
  c.transport.model = TransportModel::GordonWilke;
  c.boundary.left = c.boundary.right = c.boundary.bottom = c.boundary.top = BoundaryKind::Periodic;
  c.gravity_x = gx;
  c.gravity_y = gy;
  return c;
}

}  // namespace

TEST(GasGravity, UniformGasInPeriodicBoxFallsFreely) {
  const double gx = 2.0, gy = -9.81;
  const Grid2D grid = uniform_grid(24, 16, 0.0, 0.03, 0.0, 0.02);
  GasSolver gas(grid, periodic_air_with_gravity(gx, gy));
  InitialCondition ic;
  ic.state = {1.17, 0.0, 0.0, 101.0e3};
  gas.initialize(ic);
  const GasTotals before = gas.totals();
  const double T0 = (*gas.primitives().T)(3, 5);
  double t = 0.0;
  for (int n = 0; n < 200; ++n) {
    const double dt = gas.stable_dt();
    gas.step(dt);
    t += dt;
  }
  ASSERT_GT(t, 1e-5);
  const auto& prim = gas.primitives();
  for (int j = 0; j < grid.ny(); ++j) {
    for (int i = 0; i < grid.nx(); ++i) {
      EXPECT_NEAR((*prim.u)(i, j), gx * t, 1e-12 * std::abs(gy * t) + 1e-14);
      EXPECT_NEAR((*prim.v)(i, j), gy * t, 1e-12 * std::abs(gy * t));
      EXPECT_NEAR((*prim.rho)(i, j), 1.17, 1e-12);
      EXPECT_NEAR((*prim.T)(i, j), T0, 1e-9 * T0);  // free fall does not heat the gas
    }
  }
  const GasTotals after = gas.totals();
  EXPECT_NEAR(after.mass, before.mass, 1e-13 * before.mass);
  EXPECT_NEAR(after.momentum_x, before.mass * gx * t, 1e-11 * before.mass * std::abs(gy * t));
  EXPECT_NEAR(after.momentum_y, before.mass * gy * t, 1e-11 * before.mass * std::abs(gy * t));
  const double kinetic = 0.5 * before.mass * (gx * gx + gy * gy) * t * t;
  EXPECT_NEAR(after.energy - before.energy, kinetic, 1e-6 * kinetic + 1e-12 * before.energy);
}

TEST(GasGravity, NoCellRestsUnderGravity) {
  // Skipping on: without gravity a gas at rest costs no cell update; with gravity every
  // cell is updated every stage (3 per step) and the gas moves.
  for (const double g : {0.0, -9.81}) {
    const Grid2D grid = uniform_grid(20, 10, 0.0, 0.02, 0.0, 0.01);
    GasConfig c = periodic_air_with_gravity(0.0, g);
    c.skip_resting_cells = true;
    GasSolver gas(grid, c);
    InitialCondition ic;
    ic.state = {1.17, 0.0, 0.0, 101.0e3};
    gas.initialize(ic);
    const long long start = gas.cell_updates();
    for (int n = 0; n < 5; ++n) gas.step(gas.stable_dt());
    const long long updates = gas.cell_updates() - start;
    if (g == 0.0) {
      EXPECT_EQ(updates, 0);
      EXPECT_EQ((*gas.primitives().v)(4, 4), 0.0);
    } else {
      EXPECT_EQ(updates, 3LL * 5 * grid.nx() * grid.ny());
      EXPECT_LT((*gas.primitives().v)(4, 4), 0.0);
    }
  }
}

TEST(GasGravity, SceneKeyIsAVectorOfTwo) {
  const std::string scene = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";
  const Scene s = load_scene(scene, {"gas.gravity=[0.5, -9.81]"});
  EXPECT_EQ(s.gas.gravity_x, 0.5);
  EXPECT_EQ(s.gas.gravity_y, -9.81);
  EXPECT_FALSE(load_scene(scene, {}).gas.has_gravity());
  try {
    (void)load_scene(scene, {"gas.gravity=[-9.81]"});
    FAIL() << "a one-component gravity was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("gas.gravity"), std::string::npos) << e.what();
  }
}
