// GasSolver mechanics: eq. (17) time step (convective and viscous limits), ghost cells of each
// boundary kind, a ghost filler set in place of a boundary condition, inflow state recorded
// from the initial condition, porosity in the conserved variables, and the NumericalFailure
// message naming the cell and variable.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/core/errors.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/gas/shock_relations.hpp"
#include "solver/gas/time_step_rows.hpp"
#include "solver/gas/transport.hpp"
#include "solver/gas/thermo.hpp"

using namespace dustlift;

namespace {

Grid2D stretched_grid() {
  AxisSpec x, y;
  x.start = -0.01;
  x.end = 0.02;
  x.cell_size = 1e-3;
  x.uniform_start = 0.0;
  x.uniform_end = 0.02;
  x.cells_below = 5;
  y.start = 0.0;
  y.end = 0.012;
  y.cells = 6;
  return Grid2D(x, y, 2);
}

GasConfig air_config() {
  GasConfig c;  // thermally perfect air, Gordon-Wilke
  c.transport.model = TransportModel::Inviscid;
  return c;
}

}  // namespace

TEST(GasSolverDt, ConvectiveLimitIsTwoDimensionalCfl) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.scheme.cfl = 0.4;
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.state = {1.2, 100.0, -30.0, 1.0e5};
  gas.initialize(ic);
  const ThermallyPerfectAir air(cfg.thermo.gas_constant);
  const double c = std::sqrt(air.sound_speed_squared(1.0e5 / (1.2 * cfg.thermo.gas_constant)));
  double max_rate = 0.0;
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i)
      max_rate =
          std::max(max_rate, (100.0 + c) / grid.x().width(i) + (30.0 + c) / grid.y().width(j));
  EXPECT_NEAR(gas.stable_dt(), 0.4 / max_rate, 1e-12 * 0.4 / max_rate);
  EXPECT_NEAR(gas.sound_speed(3, 2), c, 1e-9 * c);
}

TEST(GasSolverDt, ViscousLimit) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.thermo.model = ThermoModel::CaloricallyPerfect;
  cfg.transport.model = TransportModel::Constant;
  cfg.transport.viscosity = 10.0;  // absurdly viscous: the diffusive limit wins
  cfg.transport.prandtl = 0.5;     // gamma/Pr = 2.8 > 1
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.state = {1.2, 0.0, 0.0, 1.0e5};
  gas.initialize(ic);
  const double h = 1e-3;  // smallest cell (uniform x core; y cells are 2 mm)
  EXPECT_NEAR(gas.stable_dt(), 0.25 * h * h * 1.2 / (10.0 * 1.4 / 0.5), 1e-9);
}

TEST(GasSolverDt, TableViscousLimitIsTakenWhereItBinds) {
  // Air at 300 K and 1e-3 kg/m^3 on 1 um cells: nu = 0.018 m^2/s, so the viscous limit
  // (1e-11 s) is far below the convective one (7e-10 s) and must be computed, not bounded.
  AxisSpec x, y;
  x.start = 0.0;
  x.end = 2e-5;
  x.cells = 20;
  y.start = 0.0;
  y.end = 1e-5;
  y.cells = 10;
  const Grid2D grid(x, y, 2);
  GasConfig cfg;  // thermally perfect air, Gordon-Wilke
  GasSolver gas(grid, cfg);
  const double T = 300.0, rho = 1e-3;
  InitialCondition ic;
  ic.state = {rho, 0.0, 0.0, rho * cfg.thermo.gas_constant * T};
  gas.initialize(ic);
  const ThermallyPerfectAir air(cfg.thermo.gas_constant);
  const TransportProperties tp = GordonWilkeAirTable()(T);
  const double h = 1e-6;
  const double cv = air.cp(T) - cfg.thermo.gas_constant;
  const double expected = 0.25 * h * h * rho / std::max(tp.mu, tp.lambda / cv);
  EXPECT_NEAR(gas.stable_dt(), expected, 1e-6 * expected);
  EXPECT_LT(expected, 0.1 * cfg.scheme.cfl * h / std::sqrt(air.sound_speed_squared(T)));
}

TEST(GasSolverDt, ViscousBoundIsBelowEveryCellsLimit) {
  // Rows of hot and cold, dense and thin gas on stretched cells: the bound the step uses to
  // leave out the viscous pass never exceeds the smallest limit that pass would find.
  const ThermallyPerfectAir air(287.0);
  const GordonWilkeAirTable table;
  const int n = 400;
  std::vector<double> u(n, 0.0), v(n, 0.0), T(n), rho(n), inv_dx(n), mu(n), lambda(n);
  std::uint64_t seed = 11;
  auto uniform = [&seed] {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  for (int trial = 0; trial < 20; ++trial) {
    const double t_lo = 200.0 + 2000.0 * uniform(), t_span = 3000.0 * uniform();
    for (int i = 0; i < n; ++i) {
      T[i] = t_lo + t_span * uniform();
      rho[i] = 0.01 + 5.0 * uniform();
      inv_dx[i] = 1.0 / (1e-6 + 1e-3 * uniform());
    }
    const double inv_dy = 1.0 / (1e-6 + 1e-3 * uniform());
    const TimeStepRow row{u.data(), v.data(), T.data(), rho.data(), inv_dx.data(), inv_dy,
                          n,        mu.data(), lambda.data()};
    double rate = 0.0, smallest = std::numeric_limits<double>::infinity();
    GasExtremes seen{smallest, -smallest, smallest};
    convective_rate_row(air, row, rate, seen);
    viscous_dt_row(air, table, row, smallest);
    double largest_inverse = inv_dy;
    for (double g : inv_dx) largest_inverse = std::max(largest_inverse, g);
    const double bound =
        viscous_dt_lower_bound(air, table, seen, 1.0 / (largest_inverse * largest_inverse));
    EXPECT_GT(bound, 0.0) << trial;
    EXPECT_LE(bound, smallest) << trial;
  }
  // On uniform gas and cells the bound is the limit itself, halved (its margin).
  std::fill(T.begin(), T.end(), 612.3);
  std::fill(rho.begin(), rho.end(), 0.8);
  std::fill(inv_dx.begin(), inv_dx.end(), 4000.0);
  const TimeStepRow row{u.data(), v.data(), T.data(), rho.data(), inv_dx.data(), 2000.0,
                        n,        mu.data(), lambda.data()};
  double rate = 0.0, smallest = std::numeric_limits<double>::infinity();
  GasExtremes seen{smallest, -smallest, smallest};
  convective_rate_row(air, row, rate, seen);
  viscous_dt_row(air, table, row, smallest);
  const double bound = viscous_dt_lower_bound(air, table, seen, 1.0 / (4000.0 * 4000.0));
  EXPECT_LE(bound, 0.5 * smallest);
  EXPECT_GT(bound, 0.499 * smallest);
}

TEST(GasSolverBoundaries, GhostCellsOfEachKind) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.boundary.left = BoundaryKind::SlipWall;
  cfg.boundary.right = BoundaryKind::Outflow;
  cfg.boundary.bottom = BoundaryKind::NoSlipWall;
  cfg.boundary.top = BoundaryKind::SlipWall;
  GasSolver gas(grid, cfg);
  // A non-uniform state: set conserved variables cell by cell.
  InitialCondition ic;
  ic.state = {1.2, 10.0, 5.0, 1.0e5};
  gas.initialize(ic);
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double scale = 1.0 + 0.01 * i + 0.02 * j;
      for (int k = 0; k < 4; ++k) gas.conserved(k)(i, j) *= scale;
    }
  gas.refresh_primitives();
  const GasPrimitives s = gas.primitives();
  const int nx = grid.nx(), ny = grid.ny();
  for (int j = 0; j < ny; ++j) {
    for (int g = 0; g < 2; ++g) {
      EXPECT_EQ((*s.u)(-1 - g, j), -(*s.u)(g, j));  // slip: normal velocity mirrored
      EXPECT_EQ((*s.v)(-1 - g, j), (*s.v)(g, j));
      EXPECT_EQ((*s.rho)(-1 - g, j), (*s.rho)(g, j));
      EXPECT_EQ((*s.u)(nx + g, j), (*s.u)(nx - 1, j));  // outflow: zero gradient
      EXPECT_EQ((*s.p)(nx + g, j), (*s.p)(nx - 1, j));
    }
  }
  for (int i = 0; i < nx; ++i) {
    for (int g = 0; g < 2; ++g) {
      EXPECT_EQ((*s.u)(i, -1 - g), -(*s.u)(i, g));  // no-slip: both components mirrored
      EXPECT_EQ((*s.v)(i, -1 - g), -(*s.v)(i, g));
      EXPECT_EQ((*s.T)(i, -1 - g), (*s.T)(i, g));            // adiabatic
      EXPECT_EQ((*s.v)(i, ny + g), -(*s.v)(i, ny - 1 - g));  // slip top
      EXPECT_EQ((*s.u)(i, ny + g), (*s.u)(i, ny - 1 - g));
    }
  }
}

TEST(GasSolverBoundaries, PeriodicGhostsWrap) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.boundary.left = cfg.boundary.right = cfg.boundary.bottom = cfg.boundary.top =
      BoundaryKind::Periodic;
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Riemann;
  ic.axis = 'x';
  ic.position = 0.005;
  ic.left = {1.0, 1.0, 2.0, 1e5};
  ic.right = {2.0, 3.0, 4.0, 2e5};
  gas.initialize(ic);
  const GasPrimitives s = gas.primitives();
  const int nx = grid.nx();
  for (int j = 0; j < grid.ny(); ++j) {
    EXPECT_EQ((*s.rho)(-1, j), (*s.rho)(nx - 1, j));
    EXPECT_EQ((*s.rho)(-2, j), (*s.rho)(nx - 2, j));
    EXPECT_EQ((*s.u)(nx, j), (*s.u)(0, j));
    EXPECT_EQ((*s.u)(nx + 1, j), (*s.u)(1, j));
  }
}

TEST(GasSolverBoundaries, InflowKeepsThePostShockStateFromTheInitialCondition) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.boundary.left = BoundaryKind::Inflow;  // no inflow state given: taken from the IC
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Shock;
  ic.state = {101000.0 / (288.19 * 300.0), 0.0, 0.0, 101000.0};
  ic.mach = 1.44;
  ic.position = 0.015;
  gas.initialize(ic);
  const ShockJump jump = normal_shock(ic.state, ic.mach, cfg.thermo, 'x');
  for (int n = 0; n < 20; ++n) gas.step(gas.stable_dt());
  const GasPrimitives s = gas.primitives();
  for (int j = 0; j < grid.ny(); ++j) {
    EXPECT_NEAR((*s.p)(0, j), jump.post.p, 1e-9 * jump.post.p);
    EXPECT_NEAR((*s.u)(0, j), jump.post.u, 1e-9 * jump.post.u);
    EXPECT_NEAR((*s.rho)(-1, j), jump.post.rho, 1e-12);
  }
}

/// Another part of the grid beyond the right side, at rest at a fixed state: what a
/// neighbouring rank's filler does, without the rank.
class FixedStateBeyond final : public GhostFiller {
 public:
  FixedStateBeyond(const Grid2D& grid, PrimitiveState s) : grid_(grid), s_(s) {}
  bool collective() const override { return true; }
  void fill(const PrimitiveGhosts& g) override {
    const double values[Primitive::kCount] = {s_.rho, s_.u, s_.v, s_.p, s_.T};
    for (int k = 0; k < Primitive::kCount; ++k) fill_columns(*g.fields[k], values[k]);
    ++fills;
  }
  void fill_porosity(Field2D& alpha) override { fill_columns(alpha, 1.0); }
  int fills = 0;

 private:
  void fill_columns(Field2D& f, double value) const {
    const int ng = grid_.ghosts();
    for (int j = -ng; j < grid_.ny() + ng; ++j)
      for (int g = 0; g < ng; ++g) f(grid_.nx() + g, j) = value;
  }
  Grid2D grid_;
  PrimitiveState s_;
};

TEST(GasSolverBoundaries, AFillerSetInPlaceOfASideFillsItsGhostsCornersIncluded) {
  const Grid2D grid = stretched_grid();
  GasSolver gas(grid, air_config());
  FixedStateBeyond beyond(grid, {2.0, 0.0, 0.0, 2.0e5, 350.0});
  EXPECT_THROW(gas.set_ghost_filler(GridSide::Top, &beyond), std::invalid_argument);
  gas.set_ghost_filler(GridSide::Right, &beyond);
  InitialCondition ic;
  ic.state = {1.2, 0.0, 0.0, 1.0e5};
  gas.initialize(ic);
  const GasPrimitives s = gas.primitives();
  const int nx = grid.nx(), ny = grid.ny();
  for (int j = -2; j < ny + 2; ++j) {
    EXPECT_EQ((*s.p)(nx, j), 2.0e5) << j;
    EXPECT_EQ((*s.T)(nx + 1, j), 350.0) << j;
    EXPECT_EQ((*s.p)(-1, j), 1.0e5) << j;  // the left side keeps its boundary condition
  }
  const int before = beyond.fills;
  gas.step(gas.stable_dt());
  EXPECT_EQ(beyond.fills - before, 4);             // before each stage, and the final fill
  EXPECT_GT((*s.p)(nx - 1, 2), 1.0e5);             // the higher pressure beyond pushes in
  gas.set_ghost_filler(GridSide::Right, nullptr);  // the boundary condition again (outflow)
  gas.refresh_primitives();
  EXPECT_EQ((*s.p)(nx, 2), (*s.p)(nx - 1, 2));
}

TEST(GasSolverFailure, APartOfALargerGridNamesWholeGridColumnsAndAgreesOnTheMessage) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.thermo.model = ThermoModel::CaloricallyPerfect;
  GasSolver gas(grid, cfg);
  int checks = 0;
  gas.set_fault_reporting({100, [&checks](const std::string& local) {
                             ++checks;
                             return local;
                           }});
  InitialCondition ic;
  ic.state = {1.2, 0.0, 0.0, 1.0e5};
  gas.initialize(ic);
  gas.step(gas.stable_dt());
  EXPECT_EQ(checks, 4);  // the state written from outside, then each stage
  gas.conserved(Conserved::kEnergy)(7, 4) = -1.0e6;
  gas.refresh_primitives();
  try {
    gas.step(gas.stable_dt());
    FAIL() << "expected NumericalFailure";
  } catch (const NumericalFailure& e) {
    EXPECT_NE(std::string(e.what()).find("(i, j) = (107, 4)"), std::string::npos) << e.what();
  }
}

TEST(GasSolverInitial, ShockAlongYPutsThePostShockStateBelow) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Shock;
  ic.axis = 'y';
  ic.state = {1.17, 0.0, 0.0, 1.01e5};
  ic.mach = 2.0;
  ic.position = 0.005;  // cell centres at 1, 3, 5, ... mm: j <= 1 post-shock, j >= 2 (centre not <
                        // 5 mm) pre-shock
  gas.initialize(ic);
  const ShockJump jump = normal_shock(ic.state, ic.mach, cfg.thermo, 'y');
  const GasPrimitives s = gas.primitives();
  EXPECT_NEAR((*s.v)(4, 1), jump.post.v, 1e-9 * jump.post.v);
  EXPECT_NEAR((*s.p)(4, 1), jump.post.p, 1e-9 * jump.post.p);
  EXPECT_EQ((*s.u)(4, 1), 0.0);
  EXPECT_NEAR((*s.p)(4, 2), 1.01e5, 1e-6);
  EXPECT_EQ((*s.v)(4, 2), 0.0);
}

TEST(GasSolverBoundaries, GivenInflowStateIsImposed) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.boundary.left = BoundaryKind::Inflow;
  cfg.boundary.inflow = {1.5, 50.0, 0.0, 1.2e5};
  cfg.boundary.inflow_given = true;
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.state = {1.2, 0.0, 0.0, 1.0e5};
  gas.initialize(ic);
  EXPECT_EQ((*gas.primitives().rho)(-1, 3), 1.5);
  EXPECT_EQ((*gas.primitives().u)(-2, 3), 50.0);
  EXPECT_NEAR((*gas.primitives().p)(0, 3), 1.0e5,
              1e-6);  // interior: untouched up to the T(e) solve
}

TEST(GasSolverPorosity, ConservedVariablesCarryPorosity) {
  const Grid2D grid = stretched_grid();
  GasSolver gas(grid, air_config());
  gas.porosity().fill(0.5);
  InitialCondition ic;
  ic.state = {1.2, 10.0, 0.0, 1.0e5};
  gas.initialize(ic);
  EXPECT_DOUBLE_EQ(gas.conserved(0)(2, 2), 0.6);
  EXPECT_DOUBLE_EQ(gas.conserved(1)(2, 2), 6.0);
  EXPECT_DOUBLE_EQ((*gas.primitives().rho)(2, 2), 1.2);
  EXPECT_DOUBLE_EQ((*gas.primitives().alpha_g)(2, 2), 0.5);
}

TEST(GasSolverPorosity, PressureSourceBalancesTheFluxOverAPorosityJump) {
  // alpha grad p = div(alpha p) - p grad(alpha): at rest and uniform p the two discrete parts
  // cancel, so one step leaves the gas at rest. Without the source term the velocity after
  // one step would be ~ p (alpha jump) dt / (rho dx), i.e. metres per second here.
  const Grid2D grid = stretched_grid();
  GasSolver gas(grid, air_config());
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i)
      gas.porosity()(i, j) = (i + 2 * j) % 5 == 0 ? 0.41 : 0.9 - 0.02 * i;
  InitialCondition ic;
  ic.state = {1.17, 0.0, 0.0, 1.01e5};
  gas.initialize(ic);
  gas.step(gas.stable_dt());
  for (int j = 0; j < grid.ny(); ++j) {
    for (int i = 0; i < grid.nx(); ++i) {
      EXPECT_LT(std::abs((*gas.primitives().u)(i, j)), 1e-11);
      EXPECT_LT(std::abs((*gas.primitives().v)(i, j)), 1e-11);
      EXPECT_NEAR((*gas.primitives().p)(i, j), 1.01e5, 1e-7);
    }
  }
}

TEST(GasSolverFailure, NegativePressureNamesCellAndVariable) {
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.thermo.model = ThermoModel::CaloricallyPerfect;
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.state = {1.2, 0.0, 0.0, 1.0e5};
  gas.initialize(ic);
  const double dt = gas.stable_dt();
  gas.conserved(3)(7, 4) = -1.0e6;  // negative internal energy, e.g. from a bad coupling source
  gas.refresh_primitives();
  try {
    gas.step(dt);
    FAIL() << "expected NumericalFailure";
  } catch (const NumericalFailure& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("(i, j) = (7, 4)"), std::string::npos) << m;
    EXPECT_NE(m.find("pressure"), std::string::npos) << m;
    EXPECT_NE(m.find("x = "), std::string::npos) << m;
  }
}

TEST(GasSolverFailure, NaNIsReported) {
  const Grid2D grid = stretched_grid();
  GasSolver gas(grid, air_config());
  InitialCondition ic;
  ic.state = {1.2, 0.0, 0.0, 1.0e5};
  gas.initialize(ic);
  const double dt = gas.stable_dt();
  gas.conserved(1)(3, 1) = std::nan("");
  gas.refresh_primitives();
  EXPECT_THROW(gas.step(dt), NumericalFailure);
}

TEST(GasSolverWork, ColumnWorkCountsTheCellsTheLastStageUpdated) {
  // A Riemann problem at rest (35 columns, jump between columns 14 and 15) with slip walls:
  // after one step only the columns within the stages' reach of the jump were computed.
  const Grid2D grid = stretched_grid();
  GasConfig cfg = air_config();
  cfg.skip_resting_cells = true;
  GasSolver gas(grid, cfg);
  InitialCondition ic;
  ic.kind = InitialCondition::Kind::Riemann;
  ic.axis = 'x';
  ic.position = 0.010;  // the face between columns 14 and 15 (5 stretched + 10 uniform cells)
  ic.left = {1.2, 0.0, 0.0, 2e5};
  ic.right = {1.2, 0.0, 0.0, 1e5};
  gas.initialize(ic);
  gas.step(0.5 * gas.stable_dt());
  std::vector<double> work(static_cast<std::size_t>(grid.nx()), 0.0);
  gas.add_column_work(work);
  // The third stage's ranges: the first stage's (cells whose 5-cell stencil holds both
  // states: columns 13..16), widened by 2 for each later stage: columns 9..20 hold every
  // row, the rest none.
  for (int i = 0; i < grid.nx(); ++i) {
    const double expected = i >= 9 && i <= 20 ? grid.ny() : 0.0;
    EXPECT_EQ(work[static_cast<std::size_t>(i)], expected) << i;
  }
  // It adds to what the caller has, and without skipping every cell counts.
  cfg.skip_resting_cells = false;
  GasSolver all(grid, cfg);
  all.initialize(ic);
  all.step(0.5 * all.stable_dt());
  all.add_column_work(work);
  EXPECT_EQ(work[0], grid.ny());
  EXPECT_EQ(work[10], 2.0 * grid.ny());
  std::vector<double> too_short(3);
  EXPECT_THROW(all.add_column_work(too_short), std::invalid_argument);
}
