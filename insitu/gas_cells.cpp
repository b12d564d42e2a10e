#include "insitu/gas_cells.hpp"

#include <stdexcept>
#include <string>

#include "solver/sim/derived_fields.hpp"
#include "solver/sim/gas_fields.hpp"

namespace dustlift {

void GasCellArrays::resize(std::size_t nx, std::size_t ny) {
  const auto fields = gas_fields();
  if (arrays.size() != fields.size()) {
    arrays.clear();
    for (const GasField& f : fields)
      arrays.push_back({std::string(f.name),
                        std::vector<std::vector<double>>(static_cast<std::size_t>(f.components))});
  }
  for (GasCellArray& a : arrays)
    for (auto& c : a.components) c.resize(nx * ny);
}

std::vector<double>& GasCellArrays::values(std::string_view name, std::size_t component) {
  for (GasCellArray& a : arrays)
    if (a.name == name && component < a.components.size()) return a.components[component];
  throw std::invalid_argument("GasCellArrays: no array " + std::string(name) + " component " +
                              std::to_string(component));
}

const std::vector<double>& GasCellArrays::values(std::string_view name,
                                                 std::size_t component) const {
  return const_cast<GasCellArrays&>(*this).values(name, component);
}

namespace {
std::vector<double> midpoints(const std::vector<double>& nodes) {
  std::vector<double> c(nodes.empty() ? 0 : nodes.size() - 1);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = 0.5 * (nodes[i] + nodes[i + 1]);
  return c;
}
}  // namespace

std::vector<double> GasCellArrays::x_centers() const {
  return midpoints(x_nodes);
}
std::vector<double> GasCellArrays::y_centers() const {
  return midpoints(y_nodes);
}

void GasCellArrays::check_sizes() const {
  for (const GasCellArray& a : arrays)
    for (std::size_t c = 0; c < a.components.size(); ++c)
      if (a.components[c].size() != cells())
        throw std::invalid_argument("GasCellArrays: " + a.name +
                                    (a.components.size() > 1 ? "[" + std::to_string(c) + "]" : "") +
                                    " has " + std::to_string(a.components[c].size()) +
                                    " values, expected nx*ny = " + std::to_string(cells()));
}

void gather_gas_cells(const DerivedFields& fields,
                      const std::function<double(int, int)>& sound_speed, GasCellArrays& out) {
  GasFieldInputs in = fields.inputs();
  const GasPrimitives& gas = in.gas;
  if (in.grid == nullptr || !gas.rho || !gas.u || !gas.v || !gas.p || !gas.T || !gas.alpha_g)
    throw std::invalid_argument("gather_gas_cells: the grid or a primitive field is missing");
  in.sound_speed = sound_speed;
  const Grid2D& grid = *in.grid;
  out.x_nodes = grid.x().interior_faces();
  out.y_nodes = grid.y().interior_faces();
  const int nx = grid.nx(), ny = grid.ny();
  out.resize(static_cast<std::size_t>(nx), static_cast<std::size_t>(ny));
  const auto registry = gas_fields();
  for (std::size_t f = 0; f < registry.size(); ++f) {
    const GasField& field = registry[f];
    const Field2D* made = field.made == GasFieldMade::OncePerStep ? &fields.field(f) : nullptr;
    for (std::size_t c = 0; c < out.arrays[f].components.size(); ++c) {
      std::vector<double>& to = out.arrays[f].components[c];
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          to[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j] =
              made != nullptr ? (*made)(i, j) : field.cell(in, i, j, static_cast<int>(c));
    }
  }
}

}  // namespace dustlift
