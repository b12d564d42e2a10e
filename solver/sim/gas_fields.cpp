#include "solver/sim/gas_fields.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "solver/core/derivatives.hpp"

namespace dustlift {
namespace {

double alpha_p_at(const GasFieldInputs& in, int i, int j) {
  return in.alpha_p != nullptr ? (*in.alpha_p)(i, j) : 1.0 - (*in.gas.alpha_g)(i, j);
}

/// w_z = dv/dx - du/dy (derivatives.hpp). On an MPI rank's slab the derivatives at its cuts
/// read the ghost columns, which hold the neighbours' cells: the values are the whole grid's.
void make_vorticity(const GasFieldInputs& in, Field2D& out) {
  vorticity_z_rows(*in.grid, *in.gas.u, *in.gas.v, 0, in.grid->ny(), out);
}

/// c = rho_p alpha_p: kg of real particles per m^3 of space, from the deposit the coupling
/// made; zero in a gas-only scene.
void make_dust_concentration(const GasFieldInputs& in, Field2D& out) {
  for (int j = 0; j < in.grid->ny(); ++j)
    for (int i = 0; i < in.grid->nx(); ++i)
      out(i, j) = in.alpha_p != nullptr ? in.particle_density * (*in.alpha_p)(i, j) : 0.0;
}

constexpr GasField kFields[] = {
    {"density", "kg/m^3", 1, GasFieldMade::EachOutput,
     [](const GasFieldInputs& in, int i, int j, int) { return (*in.gas.rho)(i, j); }},
    {"velocity", "m/s", 2, GasFieldMade::EachOutput,
     [](const GasFieldInputs& in, int i, int j, int c) {
       return c == 0 ? (*in.gas.u)(i, j) : (*in.gas.v)(i, j);
     }},
    {"pressure", "Pa", 1, GasFieldMade::EachOutput,
     [](const GasFieldInputs& in, int i, int j, int) { return (*in.gas.p)(i, j); }},
    {"temperature", "K", 1, GasFieldMade::EachOutput,
     [](const GasFieldInputs& in, int i, int j, int) { return (*in.gas.T)(i, j); }},
    {"mach", "1", 1, GasFieldMade::EachOutput,
     [](const GasFieldInputs& in, int i, int j, int) {
       return std::hypot((*in.gas.u)(i, j), (*in.gas.v)(i, j)) / in.sound_speed(i, j);
     }},
    {"alpha_p", "1", 1, GasFieldMade::EachOutput,
     [](const GasFieldInputs& in, int i, int j, int) { return alpha_p_at(in, i, j); }},
    {"vorticity", "1/s", 1, GasFieldMade::OncePerStep, nullptr, make_vorticity},
    {"dust_concentration", "kg/m^3", 1, GasFieldMade::OncePerStep, nullptr,
     make_dust_concentration},
};

}  // namespace

std::span<const GasField> gas_fields() {
  return kFields;
}

std::size_t gas_field_index(std::string_view name) {
  for (std::size_t k = 0; k < std::size(kFields); ++k)
    if (kFields[k].name == name) return k;
  throw std::invalid_argument("no gas field named " + std::string(name));
}

}  // namespace dustlift
