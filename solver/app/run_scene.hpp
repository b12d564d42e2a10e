#pragma once
// The run driver: one scene into one output folder, as `dustlift run` does it. `sweep` runs
// every combination through the same function.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/core/communicator.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/observer.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitNumerical = 3;
/// SIGINT or SIGTERM: the run stopped after its current step with a checkpoint written and
/// every collection consistent; `dustlift run --restart OUT/checkpoint.h5` continues it.
inline constexpr int kExitInterrupted = 4;

/// How a run ended.
struct RunOutcome {
  int exit_code = kExitSuccess;  ///< kExitSuccess, kExitNumerical or kExitInterrupted
  double time = 0.0;             ///< s, simulated time reached
  long long steps = 0;           ///< steps taken (counting from 0, also after a restart)
  double wall_seconds = 0.0;     ///< wall time of the time loop
  std::string failure;           ///< the numerical failure message (exit 3)
  std::string signal;            ///< "SIGINT" or "SIGTERM" (exit 4)
  std::string checkpoint;        ///< path of the checkpoint written last
};

struct RunOptions {
  std::string scene_label;            ///< names the scene in the log (its file)
  const Snapshot* restart = nullptr;  ///< continue from this checkpoint state
  std::string restart_folder;         ///< the folder that checkpoint's run wrote to
  bool overwrite = false;             ///< a fresh run may empty an earlier run's output folder
  bool echo_log = true;               ///< also print log lines on stderr
  bool handle_signals = true;         ///< SIGINT/SIGTERM stop the run with a checkpoint (exit 4)
  /// Set by a caller that handles the signals itself (a sweep: across its runs); replaces
  /// the handler above.
  std::function<bool()> stop_requested;
  std::string command_line;  ///< recorded in run.log, scene.resolved.toml and the outputs
  /// Observers to add before the output writers (called once; they see every step first).
  std::function<std::vector<std::unique_ptr<Observer>>()> extra_observers;
  /// Several MPI ranks: every rank calls run_scene; rank 0 checks and writes the
  /// folder, the log, the outputs and the checkpoints. Null or one rank: the serial run.
  const Communicator* comm = nullptr;
};

/// Checks the output folder (a fresh run: missing or empty, or --overwrite of an earlier run's
/// folder; a restart into its checkpoint's folder continues there), builds the simulation
/// (which validates the whole setup), then writes scene.resolved.toml, run.log, the
/// observers' files and checkpoint.h5 into the folder, and runs to the scene's end. Bad input
/// throws (SceneError, CheckpointError, std::invalid_argument) before anything is written; a
/// numerical failure is logged and returned as exit 3, an interruption as exit 4.
RunOutcome run_scene(const Scene& scene, const std::string& out_dir, const RunOptions& options);

/// "1h02m", "3m05s", "42s" ("?" when not finite).
std::string format_duration(double seconds);

}  // namespace dustlift
