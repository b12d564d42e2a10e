#pragma once
// A sweep's runs side by side: each run is a child `dustlift run` process with its share of
// the threads, so that two one-thread runs on two cores finish a study sooner than two
// two-thread runs one after another (a run's parallel efficiency is below 100 %). Results are
// the same bits as the runs one after another: a run's result does not depend on its threads.
// The same path resumes an interrupted sweep: finished runs are kept, interrupted ones continue
// from their checkpoints.
#include <optional>
#include <string>
#include <vector>

#include "solver/app/run_scene.hpp"
#include "solver/app/sweep.hpp"
#include "solver/scene/scene.hpp"

namespace dustlift {

/// What a sweep run's folder says of an earlier attempt (read from its run.log).
enum class EarlierRun {
  None,         ///< no run.log: never started (or started and left nothing)
  Finished,     ///< "done:" logged
  Failed,       ///< a numerical failure logged (running it again fails again)
  Interrupted,  ///< stopped by a signal, with a checkpoint to continue from
  Broken,       ///< started, but neither finished nor checkpointed (killed): run again
};

/// The state of a run folder and, when it ended, its outcome as the log records it.
struct EarlierRunState {
  EarlierRun state = EarlierRun::None;
  RunOutcome outcome;
};

/// Reads `folder`/run.log (and checkpoint.h5's presence; the exact end time from the
/// checkpoint written at the end, the log prints it rounded).
EarlierRunState read_earlier_run(const std::string& folder);

/// The fraction of the run done and the wall seconds since it started, from the last progress
/// line of `folder`/run.log ("t = ... ( 12.8%) ... wall 2s ..."); nullopt before the first.
std::optional<double> progress_fraction(const std::string& folder);

/// Threads per run when `jobs` runs share `threads` (0: every core) threads.
int threads_per_job(int threads, int jobs);

/// A whole-sweep estimate: the remaining wall seconds when `jobs` runs go side by side, from
/// the finished runs' wall times, the running ones' elapsed times and fractions done, and the
/// number of runs not started. NaN when nothing has progressed yet.
double sweep_eta(const std::vector<double>& finished_walls,
                 const std::vector<std::pair<double, double>>& running_elapsed_fraction,
                 std::size_t queued, int jobs);

struct SweepJobsSetup {
  const SweepDefinition* sweep = nullptr;
  const std::vector<SweepRun>* runs = nullptr;
  const std::vector<Scene>* scenes = nullptr;
  std::string out_dir;
  std::string executable;  ///< the dustlift executable the runs are started with
  int jobs = 2;
  int threads_per_run = 1;
  bool resume = false;
  std::vector<double> stations;
};

/// Runs every run of the sweep as a child process, `jobs` at a time, writing the summary after
/// each one ends (rows in the sweep's order). With `resume`, runs whose folder holds a finished
/// (or numerically failed) run of the same scene are summarised without running, interrupted
/// ones continue from their checkpoints. SIGINT/SIGTERM stop the running children (each writes
/// its checkpoint) and start no more. Returns the sweep's exit status as run_sweep says.
int run_sweep_jobs(const SweepJobsSetup& setup);

}  // namespace dustlift
