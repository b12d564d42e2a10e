#include "solver/app/sweep.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <set>

#include "solver/app/interrupt.hpp"
#include "solver/app/output_folder.hpp"
#include "solver/app/run_scene.hpp"
#include "solver/app/run_summary.hpp"
#include "solver/app/sweep_jobs.hpp"
#include "solver/app/sweep_summary.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"

namespace fs = std::filesystem;

namespace dustlift {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

/// Keeps letters, digits and ._=,+- (safe in every file system and shell); the rest becomes _.
std::string filesystem_safe(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) ||
                      std::string("._=,+-").find(c) != std::string::npos;
    out += keep ? c : '_';
  }
  return out;
}

/// Splits at `separator` where it stands outside [], {} and quotes (TOML arrays, inline
/// tables and strings keep their commas).
std::vector<std::string> split_outside_brackets(const std::string& text, char separator) {
  std::vector<std::string> parts(1);
  int depth = 0;
  char quote = 0;
  for (char c : text) {
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == separator && depth == 0) {
      parts.emplace_back();
      continue;
    }
    parts.back() += c;
  }
  return parts;
}

}  // namespace

std::vector<std::string> split_value_list(const std::string& text) {
  std::vector<std::string> values = split_outside_brackets(text, ',');
  for (auto& v : values) v = trim(v);
  return values;
}

SweepAxis parse_vary(const std::string& text) {
  SweepAxis axis;
  for (const std::string& part : split_outside_brackets(text, ';')) {  // keys that change together
    const auto eq = part.find('=');
    const std::string key = eq == std::string::npos ? "" : trim(part.substr(0, eq));
    if (key.empty())
      throw SceneError("--vary '" + text + "': expected key=v1,v2,... (keys joined by ';')");
    std::vector<std::string> values = split_value_list(part.substr(eq + 1));
    for (const auto& v : values) {
      if (v.empty()) throw SceneError("--vary '" + text + "': empty value for key '" + key + "'");
    }
    if (!axis.values.empty() && values.size() != axis.size()) {
      throw SceneError(
          fmt::format("--vary '{}': key '{}' has {} values, '{}' has {} (keys joined by ';' change "
                      "together and need as many values)",
                      text, key, values.size(), axis.keys.front(), axis.size()));
    }
    axis.keys.push_back(key);
    axis.values.push_back(std::move(values));
  }
  return axis;
}

std::vector<SweepRun> sweep_runs(const SweepDefinition& sweep) {
  std::size_t count = 1;
  for (const auto& a : sweep.axes) count *= a.size();
  std::vector<SweepRun> runs;
  std::set<std::string> used;
  for (std::size_t n = 0; n < count; ++n) {
    SweepRun run;
    std::size_t rest = n, stride = count;
    for (const auto& a : sweep.axes) {  // the first axis varies slowest
      stride /= a.size();
      const std::size_t v = rest / stride;
      rest %= stride;
      for (std::size_t k = 0; k < a.keys.size(); ++k)
        run.overrides.emplace_back(a.keys[k], a.values[k][v]);
    }
    std::string name;
    for (const auto& [key, value] : run.overrides)
      name += (name.empty() ? "" : ",") + key + "=" + value;
    name = filesystem_safe(name.empty() ? "base" : name).substr(0, 200);
    run.folder = name;
    for (int k = 2; !used.insert(run.folder).second; ++k)
      run.folder = name + "_" + std::to_string(k);
    runs.push_back(std::move(run));
  }
  return runs;
}

namespace {

/// Every combination's scene, parsed before anything runs: a bad value stops the sweep with
/// nothing written, naming the run.
std::vector<Scene> sweep_scenes(const SweepDefinition& sweep, const std::vector<SweepRun>& runs) {
  std::vector<Scene> scenes;
  for (const SweepRun& r : runs) {
    std::vector<std::string> overrides = sweep.overrides;
    for (const auto& [key, value] : r.overrides) overrides.push_back(key + "=" + value);
    try {
      scenes.push_back(load_scene(sweep.scene_path, overrides));
    } catch (const SceneError& e) {
      throw SceneError("sweep run '" + r.folder + "': " + e.what());
    }
  }
  return scenes;
}

/// The runs side by side as child processes (sweep_jobs.hpp).
int run_side_by_side(const SweepDefinition& sweep, const std::vector<SweepRun>& runs,
                     const std::vector<Scene>& scenes, const std::string& out_dir,
                     const SweepOptions& options, const std::vector<double>& stations) {
  if (options.executable.empty())
    throw SceneError("sweep: runs side by side need the dustlift executable");
  SweepJobsSetup setup;
  setup.sweep = &sweep;
  setup.runs = &runs;
  setup.scenes = &scenes;
  setup.out_dir = out_dir;
  setup.executable = options.executable;
  setup.jobs = options.jobs;
  setup.threads_per_run = options.threads > 0 ? options.threads : threads_per_job(0, options.jobs);
  setup.resume = options.resume;
  setup.stations = stations;
  std::cerr << fmt::format("sweep: {} runs, {} side by side with {} thread{} each\n", runs.size(),
                           options.jobs, setup.threads_per_run,
                           setup.threads_per_run == 1 ? "" : "s");
  return run_sweep_jobs(setup);
}

/// The runs one after another in this process, through run_scene.
int run_one_after_another(const SweepDefinition& sweep, const std::vector<SweepRun>& runs,
                          const std::vector<Scene>& scenes, const std::string& out_dir,
                          const SweepOptions& options, const std::vector<double>& stations) {
  SweepSummary summary(sweep.axes, scenes.front(), stations);

  if (options.threads > 0) omp_set_num_threads(options.threads);
  const InterruptHandler signals;  // across the runs: a Ctrl-C between two runs stops the sweep too
  int status = kExitSuccess;
  for (std::size_t n = 0; n < runs.size() && !InterruptHandler::requested(); ++n) {
    const std::string folder = (fs::path(out_dir) / runs[n].folder).string();
    RunOptions run_options;
    run_options.scene_label = sweep.scene_path;
    run_options.echo_log = false;
    run_options.command_line = options.command_line;
    run_options.stop_requested = [] { return InterruptHandler::requested(); };
    const RunOutcome outcome = run_scene(scenes[n], folder, run_options);
    RunResults results = summarise_run(folder, scenes[n], stations, sweep.lift_threshold);
    summary.add(runs[n], outcome, results, n);
    summary.write(out_dir);  // after every run: a killed sweep keeps the rows it finished
    if (outcome.exit_code != kExitSuccess && status != kExitInterrupted) status = outcome.exit_code;
    const std::string how = outcome.exit_code == kExitSuccess ? "done"
                            : outcome.exit_code == kExitNumerical
                                ? "numerical failure (exit 3)"
                                : "interrupted by " + outcome.signal + " (exit 4)";
    std::cerr << fmt::format("[{}/{}] {}: {} after {} steps, t = {:.4e} s, {:.1f} s wall\n", n + 1,
                             runs.size(), runs[n].folder, how, outcome.steps, outcome.time,
                             outcome.wall_seconds);
    if (outcome.exit_code == kExitInterrupted) {
      std::cerr << fmt::format("sweep stopped; continue that run with: dustlift run --restart {}\n",
                               outcome.checkpoint);
    }
  }
  if (InterruptHandler::requested()) status = kExitInterrupted;
  std::cerr << "summary: " << (fs::path(out_dir) / "summary.csv").string() << ", summary.h5\n";
  return status;
}

}  // namespace

int run_sweep(const SweepDefinition& sweep, const std::string& out_dir,
              const SweepOptions& options) {
  if (sweep.axes.empty())
    throw SceneError("sweep: nothing to vary (give --vary key=v1,v2 or a --study with [[vary]])");
  const std::vector<SweepRun> runs = sweep_runs(sweep);
  const std::vector<Scene> scenes = sweep_scenes(sweep, runs);
  if (options.resume && options.overwrite)
    throw SceneError("sweep: --resume keeps the earlier runs, --overwrite deletes them; give one");
  if (options.jobs < 1)
    throw SceneError(fmt::format("sweep: --jobs {}: give at least 1", options.jobs));
  const FolderUse use = options.resume      ? FolderUse::Continue
                        : options.overwrite ? FolderUse::Overwrite
                                            : FolderUse::Fresh;
  check_output_folder(out_dir, use);
  const std::vector<double> stations =
      sweep.stations.empty() ? scenes.front().output.surface_stations : sweep.stations;
  prepare_output_folder(out_dir, use);
  if (options.jobs > 1 || options.resume)
    return run_side_by_side(sweep, runs, scenes, out_dir, options, stations);
  return run_one_after_another(sweep, runs, scenes, out_dir, options, stations);
}

}  // namespace dustlift
