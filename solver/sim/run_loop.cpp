// Simulation::run: the time loop and its schedule (outputs, checkpoints, progress, stops).
#include <chrono>

#include "solver/sim/eta.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/slab_driver.hpp"
#include "solver/sim/time_targets.hpp"

namespace dustlift {

void Simulation::make_checkpoint(const RunClock& now) {
  const ScopedTimer t(timings_.checkpoints);
  const Snapshot s = snapshot();  // collective: rank 0's holds the whole state
  for (auto& o : observers_) {
    if (o->keeps_checkpoints()) o->on_checkpoint(s, now);
  }
}

RunEnd Simulation::run(const std::string& output_dir) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const auto clock_now = [&] {
    return RunClock{time_, step_, std::chrono::duration<double>(clock::now() - t0).count()};
  };
  const double time0 = time_;
  EtaMark eta{time0, 0.0};  // the previous progress report (eta.hpp)
  const double interval = scene_.output.interval;
  const double end = end_target(scene_.run.end_time, interval);
  // Progress lines every run.progress_interval wall seconds (every step for 0).
  Cadence progress = scene_.run.progress_interval > 0.0
                         ? Cadence::wall(scene_.run.progress_interval)
                         : Cadence::every_step();
  progress.start(clock_now());
  long long last_checkpoint_step = restored_ ? step_ : -1;  // a restart does not rewrite its own
  bool keeps_checkpoints = false;
  for (const auto& o : observers_) keeps_checkpoints = keeps_checkpoints || o->keeps_checkpoints();
  count_from_here();
  const GatherPlan plan = plan_gathers();
  start_observers(output_dir, plan);
  RunEnd how = RunEnd::Completed;
  double dt = 0.0;
  while (time_ < end) {
    if (scene_.run.max_steps > 0 && step_ >= scene_.run.max_steps) {
      how = RunEnd::StepLimit;
      break;
    }
    const double target = std::min(end, outputs_.next_time());
    const double remaining = target - time_;
    dt = advance(remaining);
    if (dt == remaining) time_ = target;  // exactly on the target, not a rounding short of it
    {
      const ScopedTimer t(timings_.observers);
      const bool output_due = outputs_.due(clock_now());
      observe_step(output_dir, plan, output_due);
      if (output_due) outputs_.done(clock_now());
    }
    const bool at_end = !(time_ < end);
    const bool stop = any_rank(stop_requested_ && stop_requested_());
    if (keeps_checkpoints && !at_end && !stop) {
      const RunClock now = clock_now();
      if (checkpoints_due(now)) {
        make_checkpoint(now);
        last_checkpoint_step = step_;
      }
    }
    if (progress_ && progress.due(clock_now())) {
      const RunClock now = clock_now();
      progress.done(now);
      report_progress(now, end, dt, eta);
    }
    if (stop && !at_end) {
      how = RunEnd::Interrupted;
      break;
    }
  }
  if (how != RunEnd::Interrupted) {
    const ScopedTimer t(timings_.observers);
    if (plan.gather) slabs_->gather(false, plan.output_reads);
    const StateView v = view(output_dir), piece = piece_view(output_dir);
    for (auto& o : observers_) o->on_finish(view_for(*o, v, piece));
  }
  if (keeps_checkpoints && last_checkpoint_step != step_) make_checkpoint(clock_now());
  restored_ = false;
  return how;
}

void Simulation::count_from_here() {
  first_step_ = step_;
  first_cell_updates_ = slabs_ ? slabs_->cell_updates() : gas_->cell_updates();
  first_dem_steps_ = parcels_ ? parcels_->steps() : 0;
  first_rebuilds_ = parcels_ ? parcels_->neighbour_rebuilds() : 0;
  first_kept_lists_ = parcels_ ? parcels_->kept_lists() : 0;
  first_parcel_substeps_ = parcels_ ? parcels_->parcel_substeps() : 0;
}

Simulation::GatherPlan Simulation::plan_gathers() const {
  // Observers of the whole state live on rank 0; every rank takes part in gathering what
  // they see. Those that write pieces run on every rank with its slab and need no gather.
  bool whole_observers = false;
  GatherPlan plan;
  for (const auto& o : observers_) {
    if (o->writes_pieces()) continue;
    whole_observers = true;
    plan.output_reads |= o->output_reads();
  }
  plan.gather = slabs_ && slabs_->comm().any(whole_observers);
  // Observers live on rank 0 (the others' is 0): a max is rank 0's value everywhere.
  if (plan.gather)
    plan.output_reads =
        static_cast<unsigned>(-slabs_->comm().min(-static_cast<double>(plan.output_reads)));
  return plan;
}

void Simulation::start_observers(const std::string& output_dir, const GatherPlan& plan) {
  if (plan.gather) slabs_->gather(false, plan.output_reads);
  const StateView v = view(output_dir), piece = piece_view(output_dir);
  for (auto& o : observers_) {
    if (restored_) {
      o->on_resume(view_for(*o, v, piece), resumed_from_);
    } else {
      o->on_start(view_for(*o, v, piece));
    }
  }
}

void Simulation::observe_step(const std::string& output_dir, const GatherPlan& plan,
                              bool output_due) {
  if (plan.gather) {
    bool read = output_due;
    unsigned reads = output_due ? plan.output_reads : 0u;
    const StateView now = view(output_dir);
    for (auto& o : observers_) {
      if (o->writes_pieces() || !o->reads_step(now)) continue;
      read = true;
      reads |= o->step_reads();
    }
    if (slabs_->comm().any(read)) {
      // Observers live on rank 0 (the others' is 0): a max is rank 0's value everywhere.
      reads = static_cast<unsigned>(-slabs_->comm().min(-static_cast<double>(reads)));
      slabs_->gather(false, reads);
    }
  }
  const StateView v = view(output_dir), piece = piece_view(output_dir);
  for (auto& o : observers_) o->on_step(view_for(*o, v, piece));
  if (output_due)
    for (auto& o : observers_) o->on_output(view_for(*o, v, piece));
}

bool Simulation::checkpoints_due(const RunClock& now) {
  bool due = false;
  for (auto& o : observers_) {
    if (o->keeps_checkpoints()) due = o->checkpoint_due(now) || due;
  }
  return any_rank(due);
}

void Simulation::report_progress(const RunClock& now, double end, double dt, EtaMark& eta) {
  const double eta_seconds = remaining_wall_seconds(time_, end, now.wall, eta.time, eta.wall);
  eta = {time_, now.wall};
  progress_(Progress{.time = time_,
                     .end_time = end,
                     .dt = dt,
                     .step = step_,
                     .wall_seconds = now.wall,
                     .eta_seconds = eta_seconds});
}

}  // namespace dustlift
