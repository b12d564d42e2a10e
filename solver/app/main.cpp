// dustlift command line: `run` a scene into an output folder, `sweep` combinations of scene
// overrides (docs/output.md, "Sweeps"), or print a scene's `info`.
// Exit codes: 0 success, 2 bad input (scene, options, output folder, checkpoint),
// 3 numerical failure, 4 interrupted (SIGINT/SIGTERM; checkpoint written).
// `run --restart CHECKPOINT` continues a run in its folder (docs/reliability.md).
#include <map>
#include <fmt/core.h>
#include <omp.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "insitu/checkpoint.hpp"
#include "insitu/lifting_delay.hpp"
#include "solver/app/info.hpp"
#include "solver/scene/scene_keys.hpp"
#include "solver/app/output_folder.hpp"
#include "solver/app/run_scene.hpp"
#include "solver/app/sweep.hpp"
#include "solver/app/version.hpp"
#include "solver/core/errors.hpp"
#include "solver/core/wait_policy.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/parallel/world.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/time_targets.hpp"

namespace fs = std::filesystem;
using namespace dustlift;

namespace {

/// --set keys a restart may change: when to stop, how often to write and checkpoint.
/// Anything else would change the physics of a run that is half done (and make the
/// checkpoint's state invalid) or what its series hold (a continued series would mix two
/// definitions).
void check_restart_overrides(const std::vector<std::string>& overrides) {
  static const char* const allowed[] = {"run.end_time",
                                        "run.max_steps",
                                        "run.progress_interval",
                                        "output.interval",
                                        "output.checkpoint_interval",
                                        "output.checkpoint_wall_interval"};
  for (const auto& o : overrides) {
    const std::string key = o.substr(0, o.find('='));
    if (std::find(std::begin(allowed), std::end(allowed), key) == std::end(allowed)) {
      throw SceneError(
          "--set '" + o + "': a restart continues the same run and may only change run.end_time, " +
          "run.max_steps, run.progress_interval, output.interval, output.checkpoint_interval and " +
          "output.checkpoint_wall_interval");
    }
  }
}

/// The command line as a shell would take it back (arguments with special characters quoted).
std::string command_line_of(int argc, char** argv) {
  std::string line;
  for (int k = 0; k < argc; ++k) {
    const std::string a = argv[k];
    const bool plain = !a.empty() && a.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_./=:,+-@%") == std::string::npos;
    std::string quoted = "'";
    for (char c : a) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += (k ? " " : "") + (plain ? a : quoted + "'");
  }
  return line;
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

/// `run`: a scene (or a checkpoint's scene) into its output folder.
int run_command(std::string scene_path, const std::string& restart_path, std::string out_dir,
                const std::vector<std::string>& overrides, bool overwrite,
                const std::string& command_line, const Communicator* comm) {
  if (scene_path.empty() == restart_path.empty()) {
    throw SceneError("run: give either a scene file or --restart CHECKPOINT (one of them)");
  }
  Snapshot restart;
  Scene scene;
  if (!restart_path.empty()) {
    restart = read_checkpoint(restart_path);
    check_restart_overrides(overrides);
    std::vector<std::string> all = split_lines(text_of(restart, "scene/overrides", restart_path));
    all.insert(all.end(), overrides.begin(), overrides.end());
    scene = parse_scene(text_of(restart, "scene/text", restart_path),
                        text_of(restart, "scene/name", restart_path), all);
    const auto t = restart.f64.find("run/time");
    const double t_checkpoint =
        t != restart.f64.end() && t->second.size() == 1 ? t->second[0] : 0.0;
    if (!(end_target(scene.run.end_time, scene.output.interval) > t_checkpoint)) {
      throw SceneError(
          fmt::format("key 'run.end_time': {:g} s is not after the checkpoint time {:g} s "
                      "(extend it with --set run.end_time=...)",
                      scene.run.end_time, t_checkpoint));
    }
    scene_path = restart_path;
  } else {
    scene = load_scene(scene_path, overrides);
  }
  // A restart continues the run in the folder of its checkpoint unless told otherwise.
  const std::string restart_folder =
      restart_path.empty() ? "" : fs::absolute(restart_path).parent_path().string();
  if (out_dir.empty())
    out_dir = restart_path.empty() ? (fs::path("out") / scene.run.name).string() : restart_folder;
  RunOptions options;
  options.scene_label = scene_path;
  options.restart = restart_path.empty() ? nullptr : &restart;
  options.restart_folder = restart_folder;
  options.overwrite = overwrite;
  options.command_line = command_line;
  options.comm = comm;
  return run_scene(scene, out_dir, options).exit_code;  // exit 4 printed how to continue
}

}  // namespace

int main(int argc, char** argv) {
  // Threads wait passively after a short spin unless the user chose a policy
  // (solver/core/wait_policy.hpp); libgomp reads it before main, hence the restart.
  reexec_with_default_wait_policy(argv);
  // `mpirun -np N dustlift run SCENE`: N ranks, one x-slab each (docs/parallel.md).
  const ParallelSession mpi(argc, argv);
  const std::unique_ptr<Communicator> world = make_world_communicator();
  const bool several = world->size() > 1;
  // Every rank meets the same bad input; one of them says so.
  const auto error = [&](const std::string& text) {
    if (world->is_root()) std::cerr << text << "\n";
  };
  CLI::App app{"dustlift: 2-D compressible CFD-DEM solver for shock-induced dust lifting"};
  app.set_version_flag("--version", std::string("dustlift ") + code_version());
  app.require_subcommand(1);
  const std::string command_line = command_line_of(argc, argv);
  bool overwrite = false;

  std::string scene_path, out_dir, restart_path, study_path;
  std::vector<std::string> overrides, varies;
  int threads = 0;
  SweepDefinition sweep;

  auto* run = app.add_subcommand("run", "run a scene and write its output folder");
  run->add_option("scene", scene_path, "scene file (TOML); not with --restart");
  run->add_option(
      "--restart", restart_path,
      "continue from a checkpoint (the scene comes from it; --set only for run.end_time, "
      "run.max_steps, run.progress_interval, output.*)");
  run->add_option(
      "--out,-o", out_dir,
      "output folder (default: out/<run.name>; with --restart, the checkpoint's folder)");
  run->add_flag("--overwrite", overwrite,
                "empty an existing output folder of an earlier run first");
  // One value per --set/--vary, so a scene named after them is not taken for another value.
  run->add_option("--set", overrides, "override a scene key: --set gas.scheme.cfl=0.4 (repeatable)")
      ->allow_extra_args(false);
  run->add_option("--threads,-t", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 1024));

  auto* sweep_cmd =
      app.add_subcommand("sweep", "run every combination of scene overrides and summarise them");
  sweep_cmd->add_option("scene", scene_path, "scene file (TOML); replaces the study file's scene");
  sweep_cmd
      ->add_option("--vary", varies,
                   "key=v1,v2,... (one axis; repeatable); k1=a,b;k2=c,d changes keys together")
      ->allow_extra_args(false);
  sweep_cmd->add_option("--study", study_path,
                        "study file (TOML: scene, [[vary]], set, stations, lift_threshold)");
  sweep_cmd
      ->add_option("--out,-o", out_dir,
                   "output folder: one sub-folder per run, summary.csv, summary.h5")
      ->required();
  sweep_cmd->add_option("--set", overrides, "override a scene key in every run (repeatable)")
      ->allow_extra_args(false);
  sweep_cmd->add_flag("--overwrite", overwrite,
                      "empty an existing sweep folder of an earlier sweep first");
  sweep_cmd
      ->add_option("--stations", sweep.stations,
                   "x (m) of the h(x) columns (default: output.surface_stations)")
      ->delimiter(',')
      ->allow_extra_args(false);
  sweep_cmd
      ->add_option("--lift-threshold", sweep.lift_threshold,
                   fmt::format("m above the layer top that counts as lifted (default {:g})",
                               kDefaultLiftThreshold))
      ->check(CLI::PositiveNumber);
  sweep_cmd->add_option("--threads,-t", threads, "OpenMP threads per run (default: all cores)")
      ->check(CLI::Range(1, 1024));

  auto* info = app.add_subcommand(
      "info", "print the resolved scene, enabled effects, grid and step estimate");
  std::vector<std::string> info_scenes;
  bool keys = false;
  info->add_option("scene", info_scenes, "scene file (TOML); with --keys, one or more")->required();
  info->add_flag("--keys", keys,
                 "print the scene-key reference (type, unit, default, allowed values, meaning) of "
                 "every key the scenes' parser reads, as Markdown");
  info->add_option("--set", overrides, "override a scene key (repeatable)")
      ->allow_extra_args(false);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = world->is_root() ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
    return code == 0 ? 0 : kExitBadInput;
  }
  if (threads > 0) omp_set_num_threads(threads);

  try {
    if (several && !run->parsed()) {
      throw SceneError(fmt::format(
          "only `dustlift run` runs on several MPI ranks ({} here); start `{}` without mpirun",
          world->size(), info->parsed() ? "info" : "sweep"));
    }
    if (info->parsed() && keys) {
      if (!overrides.empty()) throw SceneError("info --keys: the reference is of the scene files as written (no --set)");
      std::map<std::string, KeyFact> facts;
      for (const std::string& path : info_scenes) merge_key_facts(facts, read_scene_keys(path));
      fmt::print("{}", key_reference_markdown(facts));
      return kExitSuccess;
    }
    if (info->parsed()) {
      if (info_scenes.size() != 1) throw SceneError("info: give one scene file (several only with --keys)");
      const Scene scene = load_scene(info_scenes.front(), overrides);
      const Simulation sim(scene);
      print_info(scene, sim);
      return kExitSuccess;
    }
    if (sweep_cmd->parsed()) {
      SweepDefinition definition = study_path.empty() ? SweepDefinition{} : read_study(study_path);
      if (!scene_path.empty()) definition.scene_path = scene_path;
      if (definition.scene_path.empty())
        throw SceneError("sweep: give a scene file or a --study naming one");
      for (const auto& v : varies) definition.axes.push_back(parse_vary(v));
      definition.overrides.insert(definition.overrides.end(), overrides.begin(), overrides.end());
      if (!sweep.stations.empty()) definition.stations = sweep.stations;
      if (sweep_cmd->count("--lift-threshold") > 0)
        definition.lift_threshold = sweep.lift_threshold;
      return run_sweep(definition, out_dir, SweepOptions{threads, overwrite, command_line});
    }
    return run_command(scene_path, restart_path, out_dir, overrides, overwrite, command_line,
                       several ? world.get() : nullptr);
  } catch (const SceneError& e) {
    error(std::string("dustlift: error: ") + e.what());
    return kExitBadInput;
  } catch (const CheckpointError& e) {
    error(std::string("dustlift: error: checkpoint: ") + e.what());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    error(std::string("dustlift: error: ") + e.what());
    return kExitBadInput;
  } catch (const NumericalFailure& e) {
    error(std::string("dustlift: numerical failure: ") + e.what());
    return kExitNumerical;
  } catch (const std::bad_alloc&) {
    // The resource checks of the scene estimate the memory beforehand; this is what they missed.
    std::cerr << "dustlift: error: out of memory while setting up the run (a smaller grid or fewer "
                 "parcels)\n";
    if (several) world->abort(kExitBadInput);
    return kExitBadInput;
  } catch (const std::exception& e) {
    // Not one every rank meets (a file rank 0 could not write): the others would wait for it.
    std::cerr << "dustlift: error: " << e.what() << "\n";
    if (several) world->abort(1);
    return 1;
  }
}
