#pragma once
// A synthetic gas output for the writer tests: distinct values per cell and array.
#include <cmath>

#include "insitu/gas_cells.hpp"

namespace dustlift::testing {

/// Synthetic gas state on a stretched 7 x 5 grid with distinct values per cell and array.
inline GasCellArrays synthetic_gas() {
  GasCellArrays g;
  g.x_nodes = {0.0, 0.001, 0.0025, 0.0045, 0.007, 0.01, 0.014, 0.019};
  g.y_nodes = {0.0, 0.0005, 0.0011, 0.0018, 0.0026, 0.0035};
  g.resize(g.nx(), g.ny());
  for (std::size_t k = 0; k < g.cells(); ++k) {
    const double s = static_cast<double>(k);
    g.values("density")[k] = 1.2 + 0.01 * s;
    g.values("velocity", 0)[k] = 100.0 + s;
    g.values("velocity", 1)[k] = -3.0 * s;
    g.values("pressure")[k] = 101325.0 + 17.0 * s;
    g.values("temperature")[k] = 300.0 + 0.5 * s;
    g.values("mach")[k] = 0.001 * s;
    g.values("alpha_p")[k] = s / 100.0;
    g.values("vorticity")[k] = 1e4 * std::sin(s);
    g.values("dust_concentration")[k] = 2.5 * s;
  }
  return g;
}

}  // namespace dustlift::testing
