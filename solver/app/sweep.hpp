#pragma once
// `dustlift sweep`: runs every combination of scene overrides, each in its own folder, and
// writes a summary of result quantities (docs/output.md, "Sweeps").
#include <string>
#include <utility>
#include <vector>

#include "insitu/lifting_delay.hpp"

namespace dustlift {

/// One axis of a sweep: keys that change together, each with its own list of values (TOML
/// value text, as for --set), all lists of the same length.
struct SweepAxis {
  std::vector<std::string> keys;
  std::vector<std::vector<std::string>> values;  ///< values[k][v]: value v of key k
  std::size_t size() const { return values.empty() ? 0 : values.front().size(); }
};

/// What a sweep runs and what its summary reports.
struct SweepDefinition {
  std::string scene_path;
  std::vector<SweepAxis> axes;         ///< every combination of one value per axis is a run
  std::vector<std::string> overrides;  ///< --set for every run (before the varied keys)
  std::vector<double> stations;        ///< m, x of the h(x) columns; empty: output.surface_stations
  double lift_threshold =
      kDefaultLiftThreshold;  ///< m, rise above the layer top that counts as lifted
};

/// Splits a list of TOML values at the commas outside brackets, braces and quotes:
/// "1,2" -> {"1", "2"}; "{ p = 1, T = 2 },{ p = 3, T = 4 }" -> two inline tables.
std::vector<std::string> split_value_list(const std::string& text);

/// One --vary argument: "key=v1,v2,..." or "k1=a,b;k2=c,d" (keys that change together).
/// Throws SceneError on a malformed argument or lists of different lengths.
SweepAxis parse_vary(const std::string& text);

/// One run: its overrides (key, value text) and the folder name made of them.
struct SweepRun {
  std::vector<std::pair<std::string, std::string>> overrides;
  std::string folder;
};

/// Every combination (the first axis varies slowest), with unique filesystem-safe folder
/// names "key=value,key=value" (characters other than letters, digits and ._=,+- become _).
std::vector<SweepRun> sweep_runs(const SweepDefinition& sweep);

/// Reads a study file (TOML): `scene` (relative to the study file), `[[vary]]` tables of
/// key = [values] (keys in one table change together), optional `set` (table of key =
/// value), `stations` (m) and `lift_threshold` (m). Throws SceneError naming file and key.
SweepDefinition read_study(const std::string& path);

struct SweepOptions {
  int threads = 0;           ///< OpenMP threads per run (0: all cores; with jobs > 1, shared)
  bool overwrite = false;    ///< an existing sweep folder of an earlier sweep is emptied first
  std::string command_line;  ///< recorded in every run's outputs
  int jobs = 1;              ///< runs side by side (child processes, sweep_jobs.hpp)
  bool resume = false;       ///< keep the finished runs of an earlier sweep into the same folder
  std::string executable;    ///< the dustlift executable (jobs > 1 or resume start it)
};

/// Validates every combination (a bad one: SceneError, nothing written) and the folder
/// (missing or empty, or --overwrite, or --resume), then runs them one after another through
/// run_scene into out_dir/<folder>/ (with jobs > 1 or resume: side by side as child processes,
/// sweep_jobs.hpp) and writes out_dir/summary.csv and out_dir/summary.h5. Returns 0 if
/// every run succeeded, 3 if any failed numerically (its row records exit status 3 and the
/// sweep goes on), 4 when SIGINT/SIGTERM stopped it (the run in progress is checkpointed and
/// recorded with exit status 4; the runs after it are not started).
int run_sweep(const SweepDefinition& sweep, const std::string& out_dir,
              const SweepOptions& options);

}  // namespace dustlift
