// dustlift command line: `run` a scene into an output folder, `sweep` combinations of scene
// overrides (docs/output.md, "Sweeps"), or print a scene's `info`.
// Exit codes: 0 success, 2 bad input (scene, options, output folder, checkpoint),
// 3 numerical failure, 4 interrupted (SIGINT/SIGTERM; checkpoint written).
// `run --restart CHECKPOINT` continues a run in its folder (docs/reliability.md).
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
#include <map>
#include <string>
#include <vector>

#include "insitu/checkpoint.hpp"
#include "insitu/lifting_delay.hpp"
#include "solver/app/info.hpp"
#include "solver/app/output_folder.hpp"
#include "solver/app/run_scene.hpp"
#include "solver/app/sweep.hpp"
#include "solver/app/version.hpp"
#include "solver/core/errors.hpp"
#include "solver/core/wait_policy.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/parallel/world.hpp"
#include "solver/scene/scene_keys.hpp"
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

/// What the command line says, as CLI11 fills it.
struct CommandLine {
  std::string scene_path, out_dir, restart_path, study_path;
  std::vector<std::string> overrides, varies, info_scenes;
  int threads = 0, jobs = 1;
  bool overwrite = false, keys = false, resume = false, calibrate = false, no_estimate = false;
  SweepDefinition sweep;  ///< --stations and --lift-threshold
  CLI::App* run = nullptr;
  CLI::App* sweep_cmd = nullptr;
  CLI::App* info = nullptr;
};

void add_run_command(CLI::App& app, CommandLine& c) {
  c.run = app.add_subcommand("run", "run a scene and write its output folder");
  c.run->add_option("scene", c.scene_path, "scene file (TOML); not with --restart");
  c.run->add_option(
      "--restart", c.restart_path,
      "continue from a checkpoint (the scene comes from it; --set only for run.end_time, "
      "run.max_steps, run.progress_interval, output.*)");
  c.run->add_option(
      "--out,-o", c.out_dir,
      "output folder (default: out/<run.name>; with --restart, the checkpoint's folder)");
  c.run->add_flag("--overwrite", c.overwrite,
                  "empty an existing output folder of an earlier run first");
  // One value per --set/--vary, so a scene named after them is not taken for another value.
  c.run
      ->add_option("--set", c.overrides,
                   "override a scene key: --set gas.scheme.cfl=0.4 (repeatable)")
      ->allow_extra_args(false);
  c.run->add_option("--threads,-t", c.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
}

void add_sweep_command(CLI::App& app, CommandLine& c) {
  c.sweep_cmd =
      app.add_subcommand("sweep", "run every combination of scene overrides and summarise them");
  c.sweep_cmd->add_option("scene", c.scene_path,
                          "scene file (TOML); replaces the study file's scene");
  c.sweep_cmd
      ->add_option("--vary", c.varies,
                   "key=v1,v2,... (one axis; repeatable); k1=a,b;k2=c,d changes keys together")
      ->allow_extra_args(false);
  c.sweep_cmd->add_option("--study", c.study_path,
                          "study file (TOML: scene, [[vary]], set, stations, lift_threshold)");
  c.sweep_cmd
      ->add_option("--out,-o", c.out_dir,
                   "output folder: one sub-folder per run, summary.csv, summary.h5")
      ->required();
  c.sweep_cmd->add_option("--set", c.overrides, "override a scene key in every run (repeatable)")
      ->allow_extra_args(false);
  c.sweep_cmd->add_flag("--overwrite", c.overwrite,
                        "empty an existing sweep folder of an earlier sweep first");
  c.sweep_cmd
      ->add_option("--stations", c.sweep.stations,
                   "x (m) of the h(x) columns (default: output.surface_stations)")
      ->delimiter(',')
      ->allow_extra_args(false);
  c.sweep_cmd
      ->add_option("--lift-threshold", c.sweep.lift_threshold,
                   fmt::format("m above the layer top that counts as lifted (default {:g})",
                               kDefaultLiftThreshold))
      ->check(CLI::PositiveNumber);
  c.sweep_cmd
      ->add_option("--threads,-t", c.threads,
                   "OpenMP threads per run (default: all cores, shared among the --jobs)")
      ->check(CLI::Range(1, 1024));
  c.sweep_cmd
      ->add_option("--jobs,-j", c.jobs,
                   "runs side by side, each a process with its share of the threads (default 1)")
      ->check(CLI::Range(1, 1024));
  c.sweep_cmd->add_flag(
      "--resume", c.resume,
      "continue an interrupted sweep in its folder: finished runs are kept, interrupted ones "
      "continue from their checkpoints, the rest run");
}

void add_info_command(CLI::App& app, CommandLine& c) {
  c.info = app.add_subcommand("info",
                              "print the resolved scene, enabled effects, grid and step estimate");
  c.info->add_option("scene", c.info_scenes, "scene file (TOML); with --keys, one or more")
      ->required();
  c.info->add_flag(
      "--keys", c.keys,
      "print the scene-key reference (type, unit, default, allowed values, meaning) of "
      "every key the scenes' parser reads, as Markdown");
  c.info->add_option("--set", c.overrides, "override a scene key (repeatable)")
      ->allow_extra_args(false);
  c.info
      ->add_option("--threads,-t", c.threads,
                   "threads the cost estimate is for (default: all cores)")
      ->check(CLI::Range(1, 1024));
  c.info->add_flag("--calibrate", c.calibrate,
                   "measure this machine's rates for the cost estimate again (else cached a day)");
  c.info->add_flag("--no-estimate", c.no_estimate,
                   "leave out the cost estimate (it steps the scene for about 2 s)");
}

/// `info`: a scene's resolved keys, effects, grid and step estimate, or with --keys the
/// scene-key reference of one or more scene files.
int info_command(const CommandLine& c) {
  if (c.keys) {
    if (!c.overrides.empty())
      throw SceneError("info --keys: the reference is of the scene files as written (no --set)");
    std::map<std::string, KeyFact> facts;
    for (const std::string& path : c.info_scenes) merge_key_facts(facts, read_scene_keys(path));
    fmt::print("{}", key_reference_markdown(facts));
    return kExitSuccess;
  }
  if (c.info_scenes.size() != 1)
    throw SceneError("info: give one scene file (several only with --keys)");
  const Scene scene = load_scene(c.info_scenes.front(), c.overrides);
  const Simulation sim(scene);
  print_info(scene, sim,
             c.no_estimate ? CostEstimate::Off
             : c.calibrate ? CostEstimate::Fresh
                           : CostEstimate::Cached);
  return kExitSuccess;
}

/// `sweep`: every combination of the study's and the command line's overrides.
int sweep_command(const CommandLine& c, const std::string& command_line) {
  SweepDefinition definition = c.study_path.empty() ? SweepDefinition{} : read_study(c.study_path);
  if (!c.scene_path.empty()) definition.scene_path = c.scene_path;
  if (definition.scene_path.empty())
    throw SceneError("sweep: give a scene file or a --study naming one");
  for (const auto& v : c.varies) definition.axes.push_back(parse_vary(v));
  definition.overrides.insert(definition.overrides.end(), c.overrides.begin(), c.overrides.end());
  if (!c.sweep.stations.empty()) definition.stations = c.sweep.stations;
  if (c.sweep_cmd->count("--lift-threshold") > 0)
    definition.lift_threshold = c.sweep.lift_threshold;
  SweepOptions options;
  options.threads = c.threads;
  options.overwrite = c.overwrite;
  options.command_line = command_line;
  options.jobs = c.jobs;
  options.resume = c.resume;
  std::error_code ec;
  options.executable = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  return run_sweep(definition, c.out_dir, options);
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
  CommandLine c;
  add_run_command(app, c);
  add_sweep_command(app, c);
  add_info_command(app, c);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = world->is_root() ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
    return code == 0 ? 0 : kExitBadInput;
  }
  if (c.threads > 0) omp_set_num_threads(c.threads);

  try {
    if (several && !c.run->parsed()) {
      throw SceneError(fmt::format(
          "only `dustlift run` runs on several MPI ranks ({} here); start `{}` without mpirun",
          world->size(), c.info->parsed() ? "info" : "sweep"));
    }
    if (c.info->parsed()) return info_command(c);
    if (c.sweep_cmd->parsed()) return sweep_command(c, command_line);
    return run_command(c.scene_path, c.restart_path, c.out_dir, c.overrides, c.overwrite,
                       command_line, several ? world.get() : nullptr);
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
