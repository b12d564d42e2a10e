#pragma once
// What the .vtr and .vtp writers share: the numbered files and their .pvd collection
// (VtkSeriesFiles; a piece per rank and the file that joins them in a decomposed run), made at
// the first output, carried in checkpoints and brought back on resume.
#include <memory>
#include <string>

#include "insitu/vtk_pieces.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/core/communicator.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

class VtkFilesObserver : public Observer {
 public:
  // A decomposed run: each rank writes its piece, rank 0 the file that joins them.
  bool writes_pieces() const final { return true; }

  std::string state_key() const final { return key_; }
  void save_state(Snapshot& s, const std::string& prefix) const final {
    if (files_) {
      files_->save_state(s, prefix);
    } else {
      VtkSeriesFiles("", prefix_, extension_).save_state(s, prefix);  // nothing written yet
    }
  }
  void restore_state(const Snapshot& s, const std::string& prefix) final {
    restored_ = VtkSeriesFiles::read_state(s, prefix);
  }
  void on_resume(const StateView& view, const std::string& previous_output_dir) final {
    files_ = make_files(view);
    files_->resume(std::move(restored_), previous_output_dir);
    if (view.piece != nullptr) view.piece->comm->barrier();  // rank 0 has removed stale pieces
  }

 protected:
  /// `key`: the checkpoint group; `prefix` and `extension`: the files' (gas, vtr).
  VtkFilesObserver(std::string key, std::string prefix, std::string extension)
      : key_(std::move(key)), prefix_(std::move(prefix)), extension_(std::move(extension)) {}
  /// The run's files, made at the first call.
  VtkSeriesFiles& files(const StateView& view) {
    if (!files_) files_ = make_files(view);
    return *files_;
  }

 private:
  std::unique_ptr<VtkSeriesFiles> make_files(const StateView& view) const {
    if (view.piece != nullptr)
      return std::make_unique<VtkSeriesFiles>(
          piece_series_files(view.output_dir, prefix_, extension_, *view.piece));
    return std::make_unique<VtkSeriesFiles>(view.output_dir, prefix_, extension_);
  }

  std::string key_, prefix_, extension_;
  std::unique_ptr<VtkSeriesFiles> files_;
  VtkSeriesFiles::State restored_;
};

}  // namespace dustlift
