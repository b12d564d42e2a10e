// The gas writer observer: StateView -> GasCellArrays -> .vtr + gas.pvd (a decomposed run:
// a .vtr piece per rank and the .pvtr that joins them).
// It calls no GasSolver member itself (the sound speed comes in as a function), so it
// links and is tested without a gas solver; vtk_gas_observer_default.cpp binds
// GasSolver::sound_speed.
#include <stdexcept>

#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/vtk_files_observer.hpp"
#include "solver/sim/derived_fields.hpp"

namespace dustlift {
namespace {

class VtkGasWriter final : public VtkFilesObserver {
 public:
  explicit VtkGasWriter(SoundSpeedFunction sound_speed)
      : VtkFilesObserver("gas_vtk", "gas", "vtr"), sound_speed_(std::move(sound_speed)) {
    if (!sound_speed_) throw std::invalid_argument("VtkGasWriter: no sound speed function");
  }

  void on_output(const StateView& view) override {
    if (!view.grid) throw std::invalid_argument("VtkGasWriter: the state view has no grid");
    if (!view.derived) throw std::invalid_argument("VtkGasWriter: the state view has no fields");
    VtkSeriesFiles& out = files(view);
    if (out.last_time_is(view.time)) return;  // on_finish right after the output of that time
    const auto sound_speed = [&](int i, int j) { return sound_speed_(view, i, j); };
    if (view.piece == nullptr) {
      gather_gas_cells(*view.derived, sound_speed, cells_);
      write_gas_vtr(cells_, out.next_path(view.time), vtk_file_info_of(view));
      out.commit(view.time);
      return;
    }
    const RunPiece& piece = *view.piece;
    write_in_pieces(
        out, piece, view.time, "vtr",
        [&](const std::string& path) {
          gather_gas_cells(*view.derived, sound_speed, cells_);
          write_gas_vtr(cells_, path, vtk_file_info_of(view),
                        piece.column_bounds[static_cast<std::size_t>(piece.rank)]);
        },
        [&](const std::string& path, const std::vector<std::string>& sources) {
          write_gas_pvtr(cells_, piece.column_bounds, sources, path);
        });
  }

 private:
  SoundSpeedFunction sound_speed_;
  GasCellArrays cells_;  // reused: no reallocation after the first output
};

}  // namespace

std::unique_ptr<Observer> make_vtk_gas_writer(SoundSpeedFunction sound_speed) {
  return std::make_unique<VtkGasWriter>(std::move(sound_speed));
}

}  // namespace dustlift
