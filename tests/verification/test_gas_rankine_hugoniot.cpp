// A Mach 1.44 shock into air at 101 kPa, 300 K travels 200 mm; the state behind it must
// match the Rankine-Hugoniot jump of the same thermodynamics within 0.5 % (p, T, u), and the
// shock must be where W t puts it. Both thermodynamic models.
#include <gtest/gtest.h>

#include <cstdio>

#include "solver/gas/shock_relations.hpp"
#include "verification/gas_test_support.hpp"

using namespace dustlift;
using namespace dustlift::gas_test;

namespace {

void check_shock_run(const ThermoConfig& thermo, const char* label) {
  const double dx = 0.25e-3;  // the paper's cell size
  const int nx = 1200;        // [0, 0.3] m
  const Grid2D grid = uniform_grid(nx, 2, 0.0, nx * dx, 0.0, 20 * dx);
  GasConfig cfg;
  cfg.thermo = thermo;
  cfg.transport.model = TransportModel::Inviscid;
  cfg.boundary.left = BoundaryKind::Inflow;  // post-shock state taken from the initial condition
  cfg.boundary.right = BoundaryKind::Outflow;
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Shock;
  ic.state = {101000.0 / (thermo.gas_constant * 300.0), 0.0, 0.0, 101000.0};
  ic.mach = 1.44;
  ic.position = 0.05;
  ic.axis = 'x';
  gas.initialize(ic);
  const ShockJump jump = normal_shock(ic.state, ic.mach, thermo, 'x');
  const double end_time = 0.2 / jump.shock_speed;
  run_until(gas, end_time);
  const double x_shock = ic.position + 0.2;

  const GasPrimitives s = gas.primitives();
  double p = 0, T = 0, u = 0;
  int count = 0;
  int shock_cell = -1;
  const double p_mid = 0.5 * (ic.state.p + jump.post.p);
  for (int i = 0; i < nx; ++i) {
    const double x = grid.x().center(i);
    if (x > x_shock - 0.1 && x < x_shock - 0.02) {
      p += (*s.p)(i, 0);
      T += (*s.T)(i, 0);
      u += (*s.u)(i, 0);
      ++count;
    }
    if ((*s.p)(i, 0) > p_mid) shock_cell = i;
  }
  p /= count;
  T /= count;
  u /= count;
  const double x_found = grid.x().face(shock_cell + 1);
  std::printf("%s: p2 = %.1f Pa (theory %.1f, %+.3f%%), T2 = %.3f K (%.3f, %+.3f%%), u2 = %.3f m/s (%.3f, %+.3f%%), "
              "shock at %.5f m (W t: %.5f m)\n",
              label, p, jump.post.p, 100 * (p / jump.post.p - 1), T, jump.post_temperature,
              100 * (T / jump.post_temperature - 1), u, jump.post.u, 100 * (u / jump.post.u - 1), x_found, x_shock);
  EXPECT_NEAR(p, jump.post.p, 0.005 * jump.post.p);
  EXPECT_NEAR(T, jump.post_temperature, 0.005 * jump.post_temperature);
  EXPECT_NEAR(u, jump.post.u, 0.005 * jump.post.u);
  EXPECT_NEAR(x_found, x_shock, 2 * dx);
}

}  // namespace

TEST(RankineHugoniot, ThermallyPerfectAirMach144) {
  ThermoConfig t;  // NASA-7 air, R = 288.190
  check_shock_run(t, "thermally perfect");
}

TEST(RankineHugoniot, CaloricallyPerfectAirMach144) {
  ThermoConfig t;
  t.model = ThermoModel::CaloricallyPerfect;
  t.gamma = 1.4;
  check_shock_run(t, "calorically perfect");
}
