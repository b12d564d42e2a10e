#include "solver/app/run_scene.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "insitu/checkpoint.hpp"
#include "insitu/outputs.hpp"
#include "solver/app/interrupt.hpp"
#include "solver/app/output_folder.hpp"
#include "solver/app/version.hpp"
#include "solver/core/errors.hpp"
#include "solver/core/wait_policy.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/checkpoint_keeper.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/time_targets.hpp"

namespace fs = std::filesystem;

namespace dustlift {
namespace {

/// Writes to the terminal (unless quiet) and to the run's log file (appended to when a
/// restart continues the run in its folder).
class Log {
 public:
  /// An empty path: no file (the ranks other than 0 of a decomposed run log nothing).
  Log(const fs::path& p, bool echo, bool append) : echo_(echo) {
    if (!p.empty()) file_.open(p, append ? std::ios::app : std::ios::trunc);
  }
  void line(const std::string& s) {
    if (echo_) std::cerr << s << "\n";
    if (file_) file_ << s << "\n" << std::flush;
  }

 private:
  std::ofstream file_;
  bool echo_;
};

/// Whether a checkpoint is the end of a run that ended between two output times: its last
/// step was shortened to land there, which a single run to a later end does not do.
bool ended_off_the_output_grid(const Snapshot& s, double interval) {
  const auto end = s.f64.find("run/end_time");
  const auto t = s.f64.find("run/time");
  if (end == s.f64.end() || t == s.f64.end() || end->second.size() != 1 || t->second.size() != 1)
    return false;
  const double time = t->second[0];
  if (time != end->second[0]) return false;
  return !(interval > 0.0) ||
         multiple_time(first_multiple_after(time, interval) - 1, interval) != time;
}

/// The resolved scene with where it came from: it runs again as it is (`dustlift run`).
std::string resolved_scene_file(const Scene& scene, const RunOptions& options) {
  return fmt::format("# Written by dustlift {}\n# Command: {}\n{}", code_version(),
                     options.command_line, scene.resolved_toml);
}

}  // namespace

std::string format_duration(double s) {
  if (!std::isfinite(s)) return "?";
  const long long t = std::llround(s);
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, (t / 60) % 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

namespace {

/// The output folder may be used as `use` says; on several ranks rank 0 checks and every rank
/// stops with its verdict before any collective step.
void check_folder(const std::string& out_dir, FolderUse use, const Communicator* comm) {
  if (comm == nullptr) {
    check_output_folder(out_dir, use);
  } else {
    std::string problem;
    if (comm->is_root()) {
      try {
        check_output_folder(out_dir, use);
      } catch (const std::exception& e) {
        problem = e.what();
      }
    }
    problem = comm->first_nonempty(problem);
    if (!problem.empty()) throw SceneError(problem);
  }
}

/// The run's observers on this rank (the caller's, the outputs, the checkpoint keeper);
/// returns the checkpoint's path.
std::string add_observers(Simulation& sim, const Scene& scene, const std::string& out_dir,
                          const RunOptions& options, bool root) {
  if (root && options.extra_observers) {
    for (auto& o : options.extra_observers()) sim.add_observer(std::move(o));
  }
  // Rank 0 holds every output; the others only the writers of their pieces (the same ones,
  // in the same order, since their writes are collective).
  for (auto& o : make_output_observers(scene, out_dir, !root)) sim.add_observer(std::move(o));
  // Every rank takes part in the snapshot (rank 0 gathers the whole state); rank 0 writes it.
  const std::string checkpoint_path = (fs::path(out_dir) / "checkpoint.h5").string();
  CheckpointKeeper::Sink write_file;
  if (root)
    write_file = [checkpoint_path](const Snapshot& s) { write_checkpoint(checkpoint_path, s); };
  sim.add_observer(std::make_unique<CheckpointKeeper>(scene.output, std::move(write_file)));
  return checkpoint_path;
}

/// The log's opening lines: the code, the command, threads and ranks, a restart, the effects
/// and the layer.
void log_start(Log& log, const Simulation& sim, const Scene& scene, const RunOptions& options,
               const std::string& out_dir, const Communicator* comm, bool continuing) {
  log.line(fmt::format("dustlift {}", code_version()));
  log.line(fmt::format("command: {}", options.command_line));
  log.line(fmt::format(
      "dustlift run {} -> {} ({} threads{})", options.scene_label, out_dir, omp_get_max_threads(),
      comm != nullptr ? fmt::format(" per rank, {} MPI ranks", comm->size()) : std::string()));
  log.line("  " + wait_policy_description());
  if (options.restart != nullptr) {
    log.line(fmt::format("  restarted at t = {:.6e} s, step {}{}", sim.time(), sim.step(),
                         continuing ? ", continuing the series in this folder"
                                    : ", continuing the series of " + options.restart_folder));
  }
  if (options.restart != nullptr &&
      ended_off_the_output_grid(*options.restart, scene.output.interval)) {
    log.line(
        "  note: the checkpoint is the end of a run whose end time was not an output time; its "
        "last step "
        "was shortened to end there, so this continuation differs in the last digits from a single "
        "run to "
        "the new end (end times that are multiples of output.interval continue bit for bit)");
  }
  for (const auto& e : sim.enabled_effects()) log.line("  " + e);
  if (sim.parcels() != nullptr) {
    log.line("  " + describe_layer(scene.particles));
    if (layer_settles(scene.particles.layer)) log.line("  " + sim.bed_description());
  }
}

/// The log's closing lines: how to continue an interrupted run, or what a finished one did.
void log_end(Log& log, RunOutcome& outcome, RunEnd how, const Simulation& sim,
             const std::string& checkpoint_path) {
  if (how == RunEnd::Interrupted) {
    outcome.exit_code = kExitInterrupted;
    log.line(fmt::format(
        "dustlift: interrupted by {} at t = {:.6e} s after {} steps; checkpoint written to {}",
        outcome.signal, sim.time(), sim.step(), checkpoint_path));
    if (const int joined = InterruptHandler::joined_signals(); joined > 0)
      log.line(fmt::format(
          "dustlift: {} more signal(s) within {} ms of the first counted as the same stop request",
          joined, kStopSignalWindow.count()));
    log.line(fmt::format("continue with: dustlift run --restart {}", checkpoint_path));
  } else if (outcome.exit_code == kExitSuccess) {
    log.line(fmt::format("done: t = {:.6e} s after {} steps in {:.2f} s wall", sim.time(),
                         sim.step(), outcome.wall_seconds));
    log.line(sim.work_summary());  // collective: every rank's cell updates
  }
}

}  // namespace

RunOutcome run_scene(const Scene& scene, const std::string& out_dir, const RunOptions& options) {
  const bool continuing =
      options.restart != nullptr && same_folder(out_dir, options.restart_folder);
  const FolderUse use = continuing          ? FolderUse::Continue
                        : options.overwrite ? FolderUse::Overwrite
                                            : FolderUse::Fresh;
  const Communicator* comm =
      options.comm != nullptr && options.comm->size() > 1 ? options.comm : nullptr;
  const bool root = comm == nullptr || comm->is_root();
  check_folder(out_dir, use, comm);
  Simulation sim(scene, comm);  // validates the whole setup before anything is written
  sim.set_provenance({code_version(), options.command_line});
  const std::string checkpoint_path = add_observers(sim, scene, out_dir, options, root);
  if (options.restart != nullptr) {
    try {
      sim.restore(*options.restart, options.restart_folder);
    } catch (const SnapshotError& e) {
      throw CheckpointError(options.scene_label + ": does not fit its scene: " + e.what());
    }
  }
  if (root) {
    prepare_output_folder(out_dir, use);
    std::ofstream f(fs::path(out_dir) / "scene.resolved.toml");
    f << resolved_scene_file(scene, options);
  }
  Log log(root ? fs::path(out_dir) / "run.log" : fs::path(), root && options.echo_log, continuing);
  log_start(log, sim, scene, options, out_dir, comm, continuing);
  sim.set_log([&](const std::string& s) { log.line(s); });
  if (root)
    sim.set_progress_callback([&](const Progress& p) {
      log.line(fmt::format("t = {:.4e} s ({:5.1f}%)  step {}  dt = {:.3e} s  wall {}  ETA {}",
                           p.time, 100.0 * p.time / p.end_time, p.step, p.dt,
                           format_duration(p.wall_seconds), format_duration(p.eta_seconds)));
    });
  RunOutcome outcome;
  const auto t0 = std::chrono::steady_clock::now();
  RunEnd how = RunEnd::Completed;
  try {
    std::optional<InterruptHandler> signals;
    if (options.stop_requested) {
      sim.set_stop_request(options.stop_requested);
    } else if (options.handle_signals) {
      signals.emplace();
      sim.set_stop_request([] { return InterruptHandler::requested(); });
    }
    how = sim.run(out_dir);
    if (how == RunEnd::Interrupted) outcome.signal = InterruptHandler::signal_name();
  } catch (const NumericalFailure& e) {
    outcome.exit_code = kExitNumerical;
    outcome.failure = e.what();
    log.line(std::string("dustlift: numerical failure: ") + e.what());
  }
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  outcome.time = sim.time();
  outcome.steps = sim.step();
  if (outcome.exit_code == kExitSuccess) outcome.checkpoint = checkpoint_path;
  log_end(log, outcome, how, sim, checkpoint_path);
  return outcome;
}

}  // namespace dustlift
