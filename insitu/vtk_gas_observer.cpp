// The gas writer observer: StateView -> GasCellArrays -> .vtr + gas.pvd (a decomposed run:
// a .vtr piece per rank and the .pvtr that joins them).
// It calls no GasSolver member itself (the sound speed comes in as a function), so it
// links and is tested without a gas solver; vtk_gas_observer_default.cpp binds
// GasSolver::sound_speed.
#include <stdexcept>

#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/view_fields.hpp"
#include "insitu/vtk_pieces.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/core/communicator.hpp"

namespace dustlift {
namespace {

class VtkGasWriter final : public Observer {
 public:
  explicit VtkGasWriter(SoundSpeedFunction sound_speed) : sound_speed_(std::move(sound_speed)) {
    if (!sound_speed_) throw std::invalid_argument("VtkGasWriter: no sound speed function");
  }

  // A decomposed run: each rank writes its slab, rank 0 the .pvtr that joins them.
  bool writes_pieces() const override { return true; }

  void on_output(const StateView& view) override {
    if (!view.grid) throw std::invalid_argument("VtkGasWriter: the state view has no grid");
    if (!files_) files_ = make_files(view);
    if (files_->last_time_is(view.time)) return;  // on_finish right after the output of that time
    const auto sound_speed = [&](int i, int j) { return sound_speed_(view, i, j); };
    if (view.piece == nullptr) {
      gather_gas_cells(*view.grid, view.primitives, view.alpha_p, vorticity_of(view, vorticity_),
                       &dust_concentration_of(view, concentration_), sound_speed, cells_);
      write_gas_vtr(cells_, files_->next_path(view.time), vtk_file_info_of(view));
      files_->commit(view.time);
      return;
    }
    const RunPiece& piece = *view.piece;
    write_in_pieces(
        *files_, piece, view.time, "vtr",
        [&](const std::string& path) {
          gather_gas_cells(*view.grid, view.primitives, view.alpha_p,
                           vorticity_of(view, vorticity_),
                           &dust_concentration_of(view, concentration_), sound_speed, cells_);
          write_gas_vtr(cells_, path, vtk_file_info_of(view),
                        piece.column_bounds[static_cast<std::size_t>(piece.rank)]);
        },
        [&](const std::string& path, const std::vector<std::string>& sources) {
          write_gas_pvtr(cells_, piece.column_bounds, sources, path);
        });
  }

  std::string state_key() const override { return "gas_vtk"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    if (files_) {
      files_->save_state(s, prefix);
    } else {
      VtkSeriesFiles("", "gas", "vtr").save_state(s, prefix);  // nothing written yet
    }
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    restored_ = VtkSeriesFiles::read_state(s, prefix);
  }
  void on_resume(const StateView& view, const std::string& previous_output_dir) override {
    files_ = make_files(view);
    files_->resume(std::move(restored_), previous_output_dir);
    if (view.piece != nullptr) view.piece->comm->barrier();  // rank 0 has removed stale pieces
  }

 private:
  static std::unique_ptr<VtkSeriesFiles> make_files(const StateView& view) {
    if (view.piece != nullptr)
      return std::make_unique<VtkSeriesFiles>(
          piece_series_files(view.output_dir, "gas", "vtr", *view.piece));
    return std::make_unique<VtkSeriesFiles>(view.output_dir, "gas", "vtr");
  }

  SoundSpeedFunction sound_speed_;
  std::unique_ptr<VtkSeriesFiles> files_;
  VtkSeriesFiles::State restored_;
  GasCellArrays cells_;    // reused: no reallocation after the first output
  Field2D vorticity_;      // for a view without the run's derived fields (made by hand)
  Field2D concentration_;  // likewise
};

}  // namespace

std::unique_ptr<Observer> make_vtk_gas_writer(SoundSpeedFunction sound_speed) {
  return std::make_unique<VtkGasWriter>(std::move(sound_speed));
}

}  // namespace dustlift
