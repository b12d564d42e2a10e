#pragma once
// The run driver: one scene into one output folder, as `dustlift run` does it. `sweep` runs
// every combination through the same function.
#include <string>

#include "solver/scene/scene.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitNumerical = 3;

/// How a run ended.
struct RunOutcome {
  int exit_code = kExitSuccess;  ///< kExitSuccess or kExitNumerical
  double time = 0.0;             ///< s, simulated time reached
  long long steps = 0;           ///< steps taken (counting from 0, also after a restart)
  double wall_seconds = 0.0;     ///< wall time of the time loop
  std::string failure;           ///< the numerical failure message (exit 3)
};

struct RunOptions {
  std::string scene_label;           ///< names the scene in the log (its file)
  const Snapshot* restart = nullptr; ///< continue from this checkpoint state
  bool echo_log = true;              ///< also print log lines on stderr
};

/// Builds the simulation (which validates the whole setup), then creates `out_dir` and writes
/// scene.resolved.toml, run.log, the observers' files and checkpoint.h5 into it, and runs to
/// the scene's end. Bad input throws (SceneError, CheckpointError, std::invalid_argument)
/// before anything is written; a numerical failure is logged and returned as exit 3.
RunOutcome run_scene(const Scene& scene, const std::string& out_dir, const RunOptions& options);

/// "1h02m", "3m05s", "42s" ("?" when not finite).
std::string format_duration(double seconds);

}  // namespace dustlift
