#pragma once
// The gas output as plain arrays on the interior cells (x fastest, index i + nx*j):
// what the .vtr writer and the filters consume. Tests fill it with synthetic fields.
#include <cstddef>
#include <functional>
#include <vector>

#include "solver/core/grid.hpp"
#include "solver/gas/gas_solver.hpp"

namespace dustlift {

struct GasCellArrays {
  std::vector<double> x_nodes;             ///< m, nx+1 interior faces
  std::vector<double> y_nodes;             ///< m, ny+1 interior faces
  std::vector<double> density;             ///< kg/m^3
  std::vector<double> velocity_x;          ///< m/s
  std::vector<double> velocity_y;          ///< m/s
  std::vector<double> pressure;            ///< Pa
  std::vector<double> temperature;         ///< K
  std::vector<double> mach;                ///< 1, |u|/c
  std::vector<double> alpha_p;             ///< 1, particle volume fraction = 1 - alpha_g
  std::vector<double> vorticity;           ///< 1/s, w_z = dv/dx - du/dy
  std::vector<double> dust_concentration;  ///< kg/m^3, rho_p alpha_p

  std::size_t nx() const { return x_nodes.empty() ? 0 : x_nodes.size() - 1; }
  std::size_t ny() const { return y_nodes.empty() ? 0 : y_nodes.size() - 1; }
  std::size_t cells() const { return nx() * ny(); }
  /// Sizes every cell array to nx*ny (keeps capacity: no reallocation once sized).
  void resize(std::size_t nx, std::size_t ny);
  /// Cell centres (midpoints of the nodes).
  std::vector<double> x_centers() const;
  std::vector<double> y_centers() const;
  /// Throws std::invalid_argument when an array does not hold nx*ny values.
  void check_sizes() const;
};

/// Fills `out` from the primitive fields, `vorticity` and `dust_concentration` (interior
/// cells) and computes alpha_p and mach = sqrt(u^2+v^2) / sound_speed(i, j).
/// alpha_p: the deposited particle volume fraction, or null to use 1 - alpha_g.
/// dust_concentration: null for zeros (no particles).
void gather_gas_cells(const Grid2D& grid, const GasPrimitives& gas, const Field2D* alpha_p,
                      const Field2D& vorticity, const Field2D* dust_concentration,
                      const std::function<double(int, int)>& sound_speed, GasCellArrays& out);

}  // namespace dustlift
