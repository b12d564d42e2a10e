#pragma once
// The observer that keeps a run's checkpoints: at the first step at or after each multiple
// of output.checkpoint_interval, after any step ending at least
// output.checkpoint_wall_interval wall seconds after the last checkpoint, after the last
// step, and after the step during which a stop was requested (never after a failure;
// Simulation::run decides the last two). What a checkpoint becomes is the sink's business
// (insitu/checkpoint.hpp writes it as OUTDIR/checkpoint.h5). Steps are not shortened for
// checkpoints: the result does not depend on when they are made.
#include <functional>
#include <utility>

#include "solver/scene/scene.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

class CheckpointKeeper final : public Observer {
 public:
  using Sink = std::function<void(const Snapshot&)>;
  /// The cadences of the scene's [output] section. Make one on every rank of a decomposed
  /// run (every rank helps build the snapshot); give the sink to rank 0 only.
  CheckpointKeeper(const OutputConfig& output, Sink sink)
      : sink_(std::move(sink)),
        by_time_(Cadence::simulated(output.checkpoint_interval)),
        by_wall_(Cadence::wall(output.checkpoint_wall_interval)) {}

  void on_start(const StateView& view) override { start(view); }
  void on_resume(const StateView& view, const std::string&) override { start(view); }
  void on_output(const StateView&) override {}
  void on_finish(const StateView&) override {}
  bool writes_pieces() const override { return true; }  // on every rank, reads no view
  bool keeps_checkpoints() const override { return true; }
  bool checkpoint_due(const RunClock& now) override {
    const bool due = by_time_.due(now) || by_wall_.due(now);
    by_time_.done(now);  // on to the first multiple after this step, made or not
    return due;
  }
  void on_checkpoint(const Snapshot& snapshot, const RunClock& now) override {
    if (sink_) sink_(snapshot);
    by_wall_.done(now);
  }

 private:
  void start(const StateView& view) {
    const RunClock now{view.time, view.step, 0.0};
    by_time_.start(now);
    by_wall_.start(now);
  }
  Sink sink_;
  Cadence by_time_, by_wall_;
};

}  // namespace dustlift
