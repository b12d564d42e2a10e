// The gas writer observer: StateView -> GasCellArrays -> .vtr + gas.pvd.
// It calls no GasSolver member itself (the sound speed comes in as a function), so it
// links and is tested without a gas solver; vtk_gas_observer_default.cpp binds
// GasSolver::sound_speed.
#include <stdexcept>

#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/vtk_writers.hpp"

namespace dustlift {
namespace {

class VtkGasWriter final : public Observer {
 public:
  explicit VtkGasWriter(SoundSpeedFunction sound_speed) : sound_speed_(std::move(sound_speed)) {
    if (!sound_speed_) throw std::invalid_argument("VtkGasWriter: no sound speed function");
  }

  void on_output(const StateView& view) override {
    if (!view.grid) throw std::invalid_argument("VtkGasWriter: the state view has no grid");
    if (!files_) files_ = std::make_unique<VtkSeriesFiles>(view.output_dir, "gas", "vtr");
    if (files_->last_time_is(view.time)) return;  // on_finish right after the output of that time
    gather_gas_cells(*view.grid, view.primitives, view.alpha_p,
                     [&](int i, int j) { return sound_speed_(view, i, j); }, cells_);
    write_gas_vtr(cells_, files_->next_path(view.time), vtk_file_info_of(view));
    files_->commit(view.time);
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
    files_ = std::make_unique<VtkSeriesFiles>(view.output_dir, "gas", "vtr");
    files_->resume(std::move(restored_), previous_output_dir);
  }

 private:
  SoundSpeedFunction sound_speed_;
  std::unique_ptr<VtkSeriesFiles> files_;
  VtkSeriesFiles::State restored_;
  GasCellArrays cells_;  // reused: no reallocation after the first output
};

}  // namespace

std::unique_ptr<Observer> make_vtk_gas_writer(SoundSpeedFunction sound_speed) {
  return std::make_unique<VtkGasWriter>(std::move(sound_speed));
}

}  // namespace dustlift
