// dustlift command line: `run` a scene into an output folder, or print its `info`.
// Exit codes: 0 success, 2 bad input (scene, options, output folder, checkpoint),
// 3 numerical failure. `run --restart CHECKPOINT` continues a run (docs/reliability.md).
#include <omp.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/core.h>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "insitu/checkpoint.hpp"
#include "insitu/outputs.hpp"
#include "solver/core/errors.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/simulation.hpp"

namespace fs = std::filesystem;
using namespace dustlift;

namespace {

constexpr int kExitBadInput = 2;
constexpr int kExitNumerical = 3;

std::string format_duration(double s) {
  if (!std::isfinite(s)) return "?";
  const long long t = std::llround(s);
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, (t / 60) % 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

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

/// Writes to the terminal and to the run's log file.
class Log {
 public:
  void open(const fs::path& p) { file_.open(p); }
  void line(const std::string& s) {
    std::cerr << s << "\n";
    if (file_) file_ << s << "\n" << std::flush;
  }

 private:
  std::ofstream file_;
};

/// --set keys a restart may change: when to stop and what to write. Everything else would
/// change the physics of a run that is half done (and make the checkpoint's state invalid).
void check_restart_overrides(const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) {
    const std::string key = o.substr(0, o.find('='));
    const bool allowed = key == "run.end_time" || key == "run.max_steps" || key == "run.progress_interval" ||
                         key.rfind("output.", 0) == 0;
    if (!allowed) {
      throw SceneError("--set '" + o + "': a restart may only change run.end_time, run.max_steps, " +
                       "run.progress_interval and output.* keys");
    }
  }
}

/// Splits the newline-joined overrides a checkpoint stores.
std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> v;
  std::size_t start = 0;
  while (!s.empty() && start <= s.size()) {
    const std::size_t end = std::min(s.find('\n', start), s.size());
    v.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return v;
}

const std::string& text_of(const Snapshot& s, const std::string& name, const std::string& path) {
  const auto it = s.text.find(name);
  if (it == s.text.end()) throw CheckpointError(path + ": missing text '" + name + "'");
  return it->second;
}

void print_info(const Scene& scene, const Simulation& sim) {
  const Grid2D& g = sim.grid();
  fmt::print("scene: {}  (run name '{}')\n", scene.source_file, scene.run.name);
  fmt::print("effects on:\n");
  for (const auto& e : sim.enabled_effects()) fmt::print("  - {}\n", e);
  fmt::print("grid: {} x {} cells = {} cells; x in [{:g}, {:g}] m, y in [{:g}, {:g}] m; "
             "min dx = {:g} m, min dy = {:g} m\n",
             g.nx(), g.ny(), g.interior_cells(), g.x().start(), g.x().end(), g.y().start(),
             g.y().end(), g.x().min_width(), g.y().min_width());
  if (const ParcelSystem* p = sim.parcels()) {
    fmt::print("parcels: {}; DEM sub-step (eq. 18, nu_DEM {:g}) = {:.4g} s, ~{} per CFD step\n", p->size(),
               scene.particles.courant, p->stable_time_step(), p->substeps_for(sim.gas().stable_dt()));
  } else {
    fmt::print("parcels: 0 (gas only)\n");
  }
  const double dt0 = sim.gas().stable_dt();
  fmt::print("time: end {:g} s; initial dt (eq. 17, CFL {:g}) = {:.4g} s; estimated steps ~ {:.0f}\n",
             scene.run.end_time, scene.gas.scheme.cfl, dt0, std::ceil(scene.run.end_time / dt0));
  fmt::print("\n{}", scene.resolved_toml);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dustlift: 2-D compressible CFD-DEM solver for shock-induced dust lifting"};
  app.require_subcommand(1);

  std::string scene_path, out_dir, restart_path;
  std::vector<std::string> overrides;
  int threads = 0;

  auto* run = app.add_subcommand("run", "run a scene and write its output folder");
  run->add_option("scene", scene_path, "scene file (TOML); not with --restart");
  run->add_option("--restart", restart_path,
                  "continue from a checkpoint (the scene comes from it; --set only for run.end_time, "
                  "run.max_steps, run.progress_interval, output.*)");
  run->add_option("--out,-o", out_dir, "output folder (default: out/<run.name>)");
  run->add_option("--set", overrides, "override a scene key: --set gas.scheme.cfl=0.4 (repeatable)");
  run->add_option("--threads,-t", threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, 1024));

  auto* info = app.add_subcommand("info", "print the resolved scene, enabled effects, grid and step estimate");
  info->add_option("scene", scene_path, "scene file (TOML)")->required();
  info->add_option("--set", overrides, "override a scene key (repeatable)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  if (threads > 0) omp_set_num_threads(threads);

  Log log;
  try {
    if (run->parsed() && scene_path.empty() == restart_path.empty()) {
      throw SceneError("run: give either a scene file or --restart CHECKPOINT (one of them)");
    }
    Snapshot restart;
    Scene scene;
    if (!restart_path.empty()) {
      restart = read_checkpoint(restart_path);
      check_restart_overrides(overrides);
      std::vector<std::string> all = split_lines(text_of(restart, "scene/overrides", restart_path));
      all.insert(all.end(), overrides.begin(), overrides.end());
      scene = parse_scene(text_of(restart, "scene/text", restart_path), text_of(restart, "scene/name", restart_path), all);
      const auto t = restart.f64.find("run/time");
      const double t_checkpoint = t != restart.f64.end() && t->second.size() == 1 ? t->second[0] : 0.0;
      if (!(scene.run.end_time > t_checkpoint)) {
        throw SceneError(fmt::format("key 'run.end_time': {:g} s is not after the checkpoint time {:g} s "
                                     "(extend it with --set run.end_time=...)", scene.run.end_time, t_checkpoint));
      }
      scene_path = restart_path;
    } else {
      scene = load_scene(scene_path, overrides);
    }
    if (info->parsed()) {
      Simulation sim(scene);
      print_info(scene, sim);
      return 0;
    }
    if (out_dir.empty()) {
      if (restart_path.empty()) {
        out_dir = (fs::path("out") / scene.run.name).string();
      } else {
        // Inside the checkpoint's folder, named by the step it continues from.
        const auto s = restart.i64.find("run/step");
        const long long step = s != restart.i64.end() && s->second.size() == 1 ? s->second[0] : 0;
        out_dir = (fs::absolute(restart_path).parent_path() / fmt::format("restart_{}", step)).string();
      }
    }
    if (!restart_path.empty()) {
      std::error_code ec;
      if (fs::equivalent(out_dir, fs::absolute(restart_path).parent_path(), ec)) {
        throw SceneError("output folder '" + out_dir + "': a restart writes a new segment; it must not be the " +
                         "folder of its checkpoint (its outputs would be overwritten)");
      }
    }
    Simulation sim(scene);  // validates the whole setup before anything is written
    if (!restart_path.empty()) {
      try {
        sim.restore(restart);
      } catch (const SnapshotError& e) {
        throw CheckpointError(restart_path + ": does not fit its scene: " + e.what());
      }
    }
    prepare_output_dir(out_dir);
    {
      std::ofstream f(fs::path(out_dir) / "scene.resolved.toml");
      f << scene.resolved_toml;
    }
    log.open(fs::path(out_dir) / "run.log");
    log.line(fmt::format("dustlift run {} -> {} ({} threads)", scene_path, out_dir, omp_get_max_threads()));
    if (!restart_path.empty()) {
      log.line(fmt::format("  restarted at t = {:.6e} s, step {}", sim.time(), sim.step()));
    }
    const std::string checkpoint_path = (fs::path(out_dir) / "checkpoint.h5").string();
    sim.set_checkpoint_writer([&](const Simulation& s) { write_checkpoint(checkpoint_path, s.snapshot()); });
    for (const auto& e : sim.enabled_effects()) log.line("  " + e);
    for (auto& o : make_output_observers(scene, out_dir)) sim.add_observer(std::move(o));
    sim.set_progress_callback([&](const Progress& p) {
      log.line(fmt::format("t = {:.4e} s ({:5.1f}%)  step {}  dt = {:.3e} s  wall {}  ETA {}", p.time,
                           100.0 * p.time / p.end_time, p.step, p.dt, format_duration(p.wall_seconds),
                           format_duration(p.eta_seconds)));
    });
    const auto t0 = std::chrono::steady_clock::now();
    sim.run(out_dir);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    log.line(fmt::format("done: t = {:.6e} s after {} steps in {:.2f} s wall", sim.time(), sim.step(), wall));
    log.line(sim.work_summary());
    return 0;
  } catch (const SceneError& e) {
    std::cerr << "dustlift: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const CheckpointError& e) {
    std::cerr << "dustlift: error: checkpoint: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "dustlift: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const NumericalFailure& e) {
    log.line(std::string("dustlift: numerical failure: ") + e.what());
    return kExitNumerical;
  }
}
