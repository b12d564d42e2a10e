#pragma once
// Shared set-up for the gas solver tests: uniform grids, gamma-law configs, time loops, norms.
#include <algorithm>
#include <cmath>
#include <functional>

#include "solver/gas/gas_solver.hpp"

namespace dustlift::gas_test {

inline Grid2D uniform_grid(int nx, int ny, double x0, double x1, double y0, double y1) {
  AxisSpec x, y;
  x.start = x0;
  x.end = x1;
  x.cells = static_cast<std::size_t>(nx);
  y.start = y0;
  y.end = y1;
  y.cells = static_cast<std::size_t>(ny);
  return Grid2D(x, y, 2);
}

/// Inviscid gamma-law gas with R = 1 (the usual nondimensional shock-tube setting).
inline GasConfig ideal_gas_config(double gamma = 1.4) {
  GasConfig c;
  c.thermo.model = ThermoModel::CaloricallyPerfect;
  c.thermo.gamma = gamma;
  c.thermo.gas_constant = 1.0;
  c.transport.model = TransportModel::Inviscid;
  return c;
}

/// Advances to exactly end_time with stable steps (the last one shortened).
inline int run_until(GasSolver& gas, double end_time) {
  double t = 0.0;
  int steps = 0;
  while (t < end_time * (1.0 - 1e-14)) {
    const double dt = std::min(gas.stable_dt(), end_time - t);
    gas.step(dt);
    t += dt;
    ++steps;
  }
  return steps;
}

/// Observed order of accuracy between errors at resolution h and h/2.
inline double observed_order(double coarse_error, double fine_error) {
  return std::log(coarse_error / fine_error) / std::log(2.0);
}

}  // namespace dustlift::gas_test
