#include "solver/app/run_scene.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/core.h>
#include <fstream>
#include <iostream>

#include "insitu/checkpoint.hpp"
#include "insitu/outputs.hpp"
#include "solver/core/errors.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/simulation.hpp"

namespace fs = std::filesystem;

namespace dustlift {
namespace {

/// Creates the output folder and proves it is writable before anything else is written.
void prepare_output_dir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw SceneError("output folder '" + dir.string() + "': cannot create: " + ec.message());
  const fs::path probe = dir / ".dustlift-write-probe";
  {
    std::ofstream f(probe);
    if (!f || !(f << "x")) throw SceneError("output folder '" + dir.string() + "': not writable");
  }
  fs::remove(probe, ec);
}

/// Writes to the terminal (unless quiet) and to the run's log file.
class Log {
 public:
  Log(const fs::path& p, bool echo) : file_(p), echo_(echo) {}
  void line(const std::string& s) {
    if (echo_) std::cerr << s << "\n";
    if (file_) file_ << s << "\n" << std::flush;
  }

 private:
  std::ofstream file_;
  bool echo_;
};

}  // namespace

std::string format_duration(double s) {
  if (!std::isfinite(s)) return "?";
  const long long t = std::llround(s);
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, (t / 60) % 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

RunOutcome run_scene(const Scene& scene, const std::string& out_dir, const RunOptions& options) {
  Simulation sim(scene);  // validates the whole setup before anything is written
  if (options.restart != nullptr) {
    try {
      sim.restore(*options.restart);
    } catch (const SnapshotError& e) {
      throw CheckpointError(options.scene_label + ": does not fit its scene: " + e.what());
    }
  }
  prepare_output_dir(out_dir);
  {
    std::ofstream f(fs::path(out_dir) / "scene.resolved.toml");
    f << scene.resolved_toml;
  }
  Log log(fs::path(out_dir) / "run.log", options.echo_log);
  log.line(fmt::format("dustlift run {} -> {} ({} threads)", options.scene_label, out_dir, omp_get_max_threads()));
  if (options.restart != nullptr) log.line(fmt::format("  restarted at t = {:.6e} s, step {}", sim.time(), sim.step()));
  const std::string checkpoint_path = (fs::path(out_dir) / "checkpoint.h5").string();
  sim.set_checkpoint_writer([&](const Simulation& s) { write_checkpoint(checkpoint_path, s.snapshot()); });
  for (const auto& e : sim.enabled_effects()) log.line("  " + e);
  if (const ParcelSystem* p = sim.parcels()) {
    log.line("  " + describe_layer(scene.particles));
    if (layer_settles(scene.particles.layer)) log.line("  " + describe_bed(*p, scene.particles.layer));
  }
  for (auto& o : make_output_observers(scene, out_dir)) sim.add_observer(std::move(o));
  sim.set_progress_callback([&](const Progress& p) {
    log.line(fmt::format("t = {:.4e} s ({:5.1f}%)  step {}  dt = {:.3e} s  wall {}  ETA {}", p.time,
                         100.0 * p.time / p.end_time, p.step, p.dt, format_duration(p.wall_seconds),
                         format_duration(p.eta_seconds)));
  });
  RunOutcome outcome;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    sim.run(out_dir);
  } catch (const NumericalFailure& e) {
    outcome.exit_code = kExitNumerical;
    outcome.failure = e.what();
    log.line(std::string("dustlift: numerical failure: ") + e.what());
  }
  outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  outcome.time = sim.time();
  outcome.steps = sim.step();
  if (outcome.exit_code == kExitSuccess) {
    log.line(fmt::format("done: t = {:.6e} s after {} steps in {:.2f} s wall", sim.time(), sim.step(),
                         outcome.wall_seconds));
    log.line(sim.work_summary());
  }
  return outcome;
}

}  // namespace dustlift
