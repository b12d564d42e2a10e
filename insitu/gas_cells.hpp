#pragma once
// The gas output as plain arrays on the interior cells (x fastest, index i + nx*j), one per
// field of gas_fields() (solver/sim/gas_fields.hpp) in its order: what the .vtr writer,
// Catalyst and the filters consume. Tests fill it with synthetic fields.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace dustlift {

class DerivedFields;

struct GasCellArray {
  std::string name;                             ///< as in gas_fields()
  std::vector<std::vector<double>> components;  ///< one array of nx*ny values per component
};

struct GasCellArrays {
  std::vector<double> x_nodes;       ///< m, nx+1 interior faces
  std::vector<double> y_nodes;       ///< m, ny+1 interior faces
  std::vector<GasCellArray> arrays;  ///< gas_fields() in order (made by resize)

  std::size_t nx() const { return x_nodes.empty() ? 0 : x_nodes.size() - 1; }
  std::size_t ny() const { return y_nodes.empty() ? 0 : y_nodes.size() - 1; }
  std::size_t cells() const { return nx() * ny(); }
  /// Makes one array per gas field and sizes each to nx*ny (keeps capacity: no reallocation
  /// once sized).
  void resize(std::size_t nx, std::size_t ny);
  /// Component `component` of the field `name`; std::invalid_argument when there is none.
  std::vector<double>& values(std::string_view name, std::size_t component = 0);
  const std::vector<double>& values(std::string_view name, std::size_t component = 0) const;
  /// Cell centres (midpoints of the nodes).
  std::vector<double> x_centers() const;
  std::vector<double> y_centers() const;
  /// Throws std::invalid_argument when an array does not hold nx*ny values.
  void check_sizes() const;
};

/// Fills `out` with every field of gas_fields() for what `fields` shows: the fields made once
/// per step from `fields`, the others from its inputs cell by cell, the Mach number with
/// `sound_speed(i, j)`.
void gather_gas_cells(const DerivedFields& fields,
                      const std::function<double(int, int)>& sound_speed, GasCellArrays& out);

}  // namespace dustlift
