// GasSolver::step() allocates no memory once running (all work arrays are sized at
// construction): counted by replacing the global operator new in this test executable.
#include <gtest/gtest.h>


#include "solver/gas/gas_solver.hpp"

#include "support/allocation_counter.hpp"

using test_support::g_allocations;

using namespace dustlift;

TEST(GasSolverAllocation, StepAllocatesNothing) {
  for (TransportModel transport : {TransportModel::Inviscid, TransportModel::GordonWilke}) {
    AxisSpec x, y;
    x.start = 0.0;
    x.end = 0.05;
    x.cells = 120;
    y.start = 0.0;
    y.end = 0.02;
    y.cells = 80;  // 9600 cells: above the threading threshold, so OpenMP runs too
    const Grid2D grid(x, y, 2);
    GasConfig cfg;
    cfg.transport.model = transport;
    cfg.boundary.left = BoundaryKind::Inflow;
    cfg.boundary.bottom = BoundaryKind::NoSlipWall;
    const long at_start = g_allocations.load();
    GasSolver gas(grid, cfg);
    EXPECT_GT(g_allocations.load(), at_start);  // the counter does see the solver's allocations
    gas.porosity()(50, 3) = 0.41;
    InitialCondition ic;
    ic.kind = InitialCondition::Kind::Shock;
    ic.state = {1.17, 0.0, 0.0, 1.01e5};
    ic.mach = 1.44;
    ic.position = 0.01;
    gas.initialize(ic);
    gas.step(gas.stable_dt());  // warm-up (thread pool start-up may allocate once)
    const long before = g_allocations.load();
    for (int n = 0; n < 3; ++n) gas.step(gas.stable_dt());
    (void)gas.totals();
    EXPECT_EQ(g_allocations.load() - before, 0);
  }
}
