#pragma once
// The registry of the gas-side output fields: every field the gas writers (.vtr, .pvtr) and
// Catalyst's "gas" channel hold, in the order they hold them, with its unit, its producer and
// when it is made. DerivedFields makes the fields made once per step; gather_gas_cells
// (insitu/gas_cells.hpp) reads the others cell by cell at an output. A new gas field is its
// entry here and its producer: the writers, Catalyst and DerivedFields iterate this list.
#include <cstddef>
#include <functional>
#include <span>
#include <string_view>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/gas/gas_solver.hpp"

namespace dustlift {

/// What a gas field is made from: the grid and state one view shows.
struct GasFieldInputs {
  const Grid2D* grid = nullptr;
  GasPrimitives gas{};
  /// The deposited particle volume fraction (eq. 12); null: 1 - alpha_g (gas-only scenes).
  const Field2D* alpha_p = nullptr;
  double particle_density = 0.0;  ///< kg/m^3 of the real particles; 0 without particles
  /// The gas's sound speed at cell (i, j) (the Mach number); set by the writer that asks.
  std::function<double(int, int)> sound_speed;
};

enum class GasFieldMade {
  EachOutput,  ///< read cell by cell from the state when an output gathers it
  OncePerStep  ///< a whole field (derivatives need neighbours), made by DerivedFields
};

struct GasField {
  std::string_view name;  ///< the array's name in .vtr files and Catalyst
  std::string_view unit;  ///< SI; "1" for dimensionless
  int components = 1;     ///< 2: a vector (x, y), written with z = 0
  GasFieldMade made = GasFieldMade::EachOutput;
  /// EachOutput: component c of interior cell (i, j).
  double (*cell)(const GasFieldInputs&, int i, int j, int c) = nullptr;
  /// OncePerStep: the interior cells of `out` (a field of the inputs' grid).
  void (*make)(const GasFieldInputs&, Field2D& out) = nullptr;
};

/// Every gas output field, in file order.
std::span<const GasField> gas_fields();
/// The index of `name` in gas_fields(); std::invalid_argument when there is none.
std::size_t gas_field_index(std::string_view name);

}  // namespace dustlift
