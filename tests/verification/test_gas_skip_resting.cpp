// Skipping resting gas is exact: a shock running into gas at rest over a porous layer, and a
// pressure pulse in the middle of a tube at rest on both sides, give bitwise the same
// conserved and primitive fields with skipping on and off, while skipping does measurably
// fewer cell-stage updates.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#include "solver/gas/gas_solver.hpp"

using namespace dustlift;

namespace {

struct Problem {
  GasConfig cfg;
  InitialCondition ic;
  bool layer = false;  ///< a packed layer (alpha 0.41) in the bottom rows from x = 0
};

GasSolver build(const Problem& pb, bool skip) {
  AxisSpec x, y;
  x.start = -0.02;
  x.end = 0.06;
  x.cell_size = 0.5e-3;
  x.uniform_start = 0.0;
  x.uniform_end = 0.06;
  x.cells_below = 10;
  y.start = 0.0;
  y.end = 0.02;
  y.cell_size = 0.5e-3;
  y.uniform_start = 0.0;
  y.uniform_end = 0.012;
  y.cells_above = 6;
  const Grid2D grid(x, y, 2);
  GasConfig cfg = pb.cfg;
  cfg.skip_resting_cells = skip;
  GasSolver gas(grid, cfg);
  if (pb.layer) {
    for (int j = 0; j < 4; ++j)
      for (int i = 10; i < grid.nx(); ++i) gas.porosity()(i, j) = 0.41 + 0.01 * (i % 5);
  }
  gas.initialize(pb.ic);
  return gas;
}

bool same_bits(const Field2D& a, const Field2D& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_skip_exact(const Problem& pb, int steps, const char* name) {
  GasSolver on = build(pb, true), off = build(pb, false);
  for (int n = 0; n < steps; ++n) {
    const double dt_on = on.stable_dt(), dt_off = off.stable_dt();
    ASSERT_EQ(dt_on, dt_off) << "step " << n;
    on.step(dt_on);
    off.step(dt_off);
  }
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(same_bits(on.conserved(k), off.conserved(k))) << name << " variable " << k;
  const GasPrimitives a = on.primitives(), b = off.primitives();
  EXPECT_TRUE(same_bits(*a.rho, *b.rho) && same_bits(*a.u, *b.u) && same_bits(*a.v, *b.v) &&
              same_bits(*a.p, *b.p) && same_bits(*a.T, *b.T))
      << name;
  const double ratio = static_cast<double>(on.cell_updates()) / static_cast<double>(off.cell_updates());
  std::printf("%s: %d steps, cell-stage updates with skipping / without = %.3f\n", name, steps, ratio);
  EXPECT_LT(ratio, 0.8) << "skipping should avoid the resting part of the domain";
  // Something did move: the test is not trivially at rest.
  double max_u = 0.0;
  for (int j = 0; j < on.grid().ny(); ++j)
    for (int i = 0; i < on.grid().nx(); ++i) max_u = std::max(max_u, std::abs((*a.u)(i, j)));
  EXPECT_GT(max_u, 10.0);
}

}  // namespace

TEST(GasSkipResting, ShockIntoPorousLayerViscousThermallyPerfect) {
  Problem pb;
  pb.cfg.boundary = {BoundaryKind::Inflow, BoundaryKind::Outflow, BoundaryKind::NoSlipWall, BoundaryKind::SlipWall};
  pb.ic.kind = InitialCondition::Kind::Shock;
  pb.ic.state = {101000.0 / (288.19 * 300.0), 0.0, 0.0, 101000.0, 300.0};
  pb.ic.mach = 1.44;
  pb.ic.position = -0.005;
  pb.layer = true;
  expect_skip_exact(pb, 60, "shock into porous layer");
}

TEST(GasSkipResting, PulseAtRestOnBothSidesInviscidPerfectGas) {
  Problem pb;
  pb.cfg.thermo.model = ThermoModel::CaloricallyPerfect;
  pb.cfg.transport.model = TransportModel::Inviscid;
  pb.cfg.scheme.limiter = Limiter::VanAlbada;
  pb.cfg.boundary = {BoundaryKind::SlipWall, BoundaryKind::SlipWall, BoundaryKind::SlipWall, BoundaryKind::SlipWall};
  // A high-pressure slab in the middle: the waves run both ways into gas at rest.
  pb.ic.kind = InitialCondition::Kind::Riemann;
  pb.ic.left = {1.2, 0.0, 0.0, 2.0e5};
  pb.ic.right = {1.2, 0.0, 0.0, 1.0e5};
  pb.ic.position = 0.02;
  expect_skip_exact(pb, 80, "pulse, rest on both sides");
}
