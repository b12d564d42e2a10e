// make_vtk_gas_writer() with the gas solver's own sound speed. Its own file: it is the only
// insitu object that needs GasSolver's definition at link time.
#include <stdexcept>

#include "insitu/observers.hpp"

namespace dustlift {

std::unique_ptr<Observer> make_vtk_gas_writer() {
  return make_vtk_gas_writer([](const StateView& view, int i, int j) {
    if (!view.gas) throw std::invalid_argument("VtkGasWriter: the state view has no gas solver");
    return view.gas->sound_speed(i, j);
  });
}

}  // namespace dustlift
