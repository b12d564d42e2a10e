// The gas writer observer: StateView -> GasCellArrays -> .vtr + gas.pvd.
// Kept apart from vtk_writers.cpp so code that only writes plain arrays (tests, tools)
// does not need a linked GasSolver.
#include <stdexcept>

#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/vtk_writers.hpp"

namespace dustlift {
namespace {

class VtkGasWriter final : public Observer {
 public:
  void on_output(const StateView& view) override {
    if (!view.grid || !view.gas)
      throw std::invalid_argument("VtkGasWriter: the state view has no grid or gas solver");
    if (!files_) files_ = std::make_unique<VtkSeriesFiles>(view.output_dir, "gas", "vtr");
    const GasSolver* gas = view.gas;
    gather_gas_cells(*view.grid, view.primitives,
                     [gas](int i, int j) { return gas->sound_speed(i, j); }, cells_);
    write_gas_vtr(cells_, files_->next_path(view.time));
    files_->commit(view.time);
  }

 private:
  std::unique_ptr<VtkSeriesFiles> files_;
  GasCellArrays cells_;  // reused: no reallocation after the first output
};

}  // namespace

std::unique_ptr<Observer> make_vtk_gas_writer() { return std::make_unique<VtkGasWriter>(); }

}  // namespace dustlift
