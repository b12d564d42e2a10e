#include "solver/app/sweep_jobs.hpp"

#include <fcntl.h>
#include <fmt/core.h>
#include <omp.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <thread>

#include "insitu/checkpoint.hpp"
#include "solver/app/interrupt.hpp"
#include "solver/app/output_folder.hpp"
#include "solver/app/run_summary.hpp"
#include "solver/app/sweep_summary.hpp"
#include "solver/scene/table_reader.hpp"

extern char** environ;

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace dustlift {
namespace {

std::vector<std::string> log_lines(const std::string& folder) {
  std::vector<std::string> lines;
  std::ifstream f(fs::path(folder) / "run.log");
  for (std::string line; std::getline(f, line);) lines.push_back(line);
  return lines;
}

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

/// "t = 3.8509e-05 s ( 12.8%)  step 160  ..." -> time, percent and step.
bool parse_progress(const std::string& line, double& time, double& percent, long long& step) {
  return std::sscanf(line.c_str(), "t = %lf s (%lf%%) step %lld", &time, &percent, &step) == 3;
}

/// A resolved scene's keys and values: without the comment lines that head it (the code, the
/// command line, the source file and the overrides, which name the same scene differently).
std::string scene_body(std::istream& in) {
  std::string text, line;
  bool header = true;
  while (std::getline(in, line)) {
    if (header && starts_with(line, "#")) continue;
    header = false;
    text += line + "\n";
  }
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::string scene_body_of_folder(const std::string& folder) {
  std::ifstream f(fs::path(folder) / "scene.resolved.toml");
  return scene_body(f);
}

std::string scene_body_of(const Scene& scene) {
  std::istringstream in(scene.resolved_toml);
  return scene_body(in);
}

/// A child `dustlift run`: its output goes to its run.log only (the sweep prints the progress).
pid_t spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0)
    throw SceneError(fmt::format("sweep: cannot start '{}': {}", args[0], std::strerror(error)));
  return pid;
}

struct Child {
  std::size_t index = 0;
  pid_t pid = -1;
  Clock::time_point started;
  bool told_to_stop = false;
};

}  // namespace

namespace {

/// The time and step exactly as the run ended (the log prints them rounded): from the
/// checkpoint written at the end, when it is that state.
void exact_end_from_checkpoint(const std::string& folder, RunOutcome& outcome) {
  const fs::path path = fs::path(folder) / "checkpoint.h5";
  if (!fs::exists(path)) return;
  try {
    const Snapshot s = read_checkpoint(path.string());
    const auto t = s.f64.find("run/time");
    const auto step = s.i64.find("run/step");
    if (t == s.f64.end() || step == s.i64.end() || t->second.size() != 1 ||
        step->second.size() != 1)
      return;
    if (step->second[0] != outcome.steps) return;  // an earlier checkpoint, not the end
    outcome.time = t->second[0];
  } catch (const std::exception&) {
    // The rounded values of the log stand.
  }
}

}  // namespace

EarlierRunState read_earlier_run(const std::string& folder) {
  EarlierRunState s;
  const std::vector<std::string> lines = log_lines(folder);
  if (lines.empty()) return s;
  s.state = EarlierRun::Broken;
  double last_time = 0.0, percent = 0.0;
  long long last_step = 0;
  for (const std::string& line : lines) {
    double t = 0.0;
    long long step = 0;
    double wall = 0.0;
    char name[16] = {};
    if (parse_progress(line, t, percent, step)) {
      last_time = t;
      last_step = step;
    } else if (std::sscanf(line.c_str(), "done: t = %lf s after %lld steps in %lf s wall", &t,
                           &step, &wall) == 3) {
      s.state = EarlierRun::Finished;
      s.outcome = RunOutcome{kExitSuccess, t, step, wall, "", "", ""};
      s.outcome.checkpoint = (fs::path(folder) / "checkpoint.h5").string();
    } else if (starts_with(line, "dustlift: numerical failure: ")) {
      s.state = EarlierRun::Failed;
      s.outcome.exit_code = kExitNumerical;
      s.outcome.failure = line.substr(std::string("dustlift: numerical failure: ").size());
      s.outcome.time = last_time;
      s.outcome.steps = last_step;
    } else if (std::sscanf(line.c_str(),
                           "dustlift: interrupted by %15s at t = %lf s after %lld steps", name, &t,
                           &step) == 3) {
      s.state = fs::exists(fs::path(folder) / "checkpoint.h5") ? EarlierRun::Interrupted
                                                               : EarlierRun::Broken;
      s.outcome.exit_code = kExitInterrupted;
      s.outcome.signal = name;
      s.outcome.time = t;
      s.outcome.steps = step;
      s.outcome.checkpoint = (fs::path(folder) / "checkpoint.h5").string();
    } else if (starts_with(line, "  restarted at t = ")) {
      // A continuation: what came before it ended is superseded by what follows.
      s.state = EarlierRun::Broken;
    }
  }
  if (s.state == EarlierRun::Finished || s.state == EarlierRun::Interrupted)
    exact_end_from_checkpoint(folder, s.outcome);
  return s;
}

std::optional<double> progress_fraction(const std::string& folder) {
  std::optional<double> fraction;
  for (const std::string& line : log_lines(folder)) {
    double t = 0.0, percent = 0.0;
    long long step = 0;
    if (parse_progress(line, t, percent, step)) fraction = std::clamp(percent / 100.0, 0.0, 1.0);
  }
  return fraction;
}

int threads_per_job(int threads, int jobs) {
  const int total = threads > 0 ? threads : omp_get_num_procs();
  return std::max(1, total / std::max(1, jobs));
}

double sweep_eta(const std::vector<double>& finished_walls,
                 const std::vector<std::pair<double, double>>& running_elapsed_fraction,
                 std::size_t queued, int jobs) {
  // A run's whole wall time: the finished ones', and the running ones' elapsed time over
  // their fraction done; the runs not started take the mean of those.
  std::vector<double> whole = finished_walls;
  double remaining = 0.0;
  for (const auto& [elapsed, fraction] : running_elapsed_fraction) {
    if (!(fraction > 0.0)) continue;
    whole.push_back(elapsed / fraction);
    remaining += elapsed / fraction - elapsed;
  }
  if (whole.empty()) return std::numeric_limits<double>::quiet_NaN();
  double mean = 0.0;
  for (double w : whole) mean += w;
  mean /= static_cast<double>(whole.size());
  return (remaining + static_cast<double>(queued) * mean) / std::max(1, jobs);
}

namespace {

/// The sweep's runs as child processes: what each has done, who runs, and the summary.
class SweepJobs {
 public:
  explicit SweepJobs(const SweepJobsSetup& setup)
      : setup_(setup),
        runs_(*setup.runs),
        scenes_(*setup.scenes),
        n_(runs_.size()),
        outcomes_(n_),
        results_(n_),
        restart_from_(n_) {}

  int run() {
    if (setup_.resume) read_earlier_runs();
    keep_earlier_runs();
    const InterruptHandler signals;  // forwarded to the children, which checkpoint and stop
    while (true) {
      start_runs();
      if (running_.empty()) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (InterruptHandler::requested()) forward_stop();
      reap_ended();
      report_progress();
    }
    if (InterruptHandler::requested()) status_ = kExitInterrupted;
    std::cerr << "summary: " << (fs::path(setup_.out_dir) / "summary.csv").string()
              << ", summary.h5\n";
    return status_;
  }

 private:
  std::string folder_of(std::size_t k) const {
    return (fs::path(setup_.out_dir) / runs_[k].folder).string();
  }

  /// What an earlier attempt left: finished and failed runs are kept, interrupted ones continue.
  void read_earlier_runs() {
    for (std::size_t k = 0; k < n_; ++k) {
      const std::string folder = folder_of(k);
      const EarlierRunState earlier = read_earlier_run(folder);
      if (earlier.state == EarlierRun::None) continue;
      if (scene_body_of_folder(folder) != scene_body_of(scenes_[k]))
        throw SceneError(fmt::format(
            "sweep --resume: '{}' holds a run of another scene than this sweep's run '{}' (was "
            "the study changed? give a new --out, or --overwrite)",
            folder, runs_[k].folder));
      if (earlier.state == EarlierRun::Finished || earlier.state == EarlierRun::Failed) {
        outcomes_[k] = earlier.outcome;
        if (earlier.state == EarlierRun::Failed) status_ = kExitNumerical;
        if (earlier.state == EarlierRun::Finished)
          finished_walls_.push_back(earlier.outcome.wall_seconds);
      } else if (earlier.state == EarlierRun::Interrupted) {
        restart_from_[k] = earlier.outcome.checkpoint;
      }
    }
  }

  /// The kept runs' results first, so that every summary written holds only complete rows.
  void keep_earlier_runs() {
    bool any = false;
    for (std::size_t k = 0; k < n_; ++k) {
      if (!outcomes_[k]) continue;
      results_[k] = results_of(k);
      any = true;
    }
    if (any) write_summary();
    for (std::size_t k = 0; k < n_; ++k)
      if (outcomes_[k]) announce(k, " (kept from the earlier sweep)");
  }

  RunResults results_of(std::size_t k) const {
    return summarise_run(folder_of(k), scenes_[k], setup_.stations, setup_.sweep->lift_threshold);
  }

  void write_summary() const {
    SweepSummary summary(setup_.sweep->axes, scenes_.front(), setup_.stations);
    for (std::size_t k = 0; k < n_; ++k)
      if (outcomes_[k]) summary.add(runs_[k], *outcomes_[k], results_[k], k);
    summary.write(setup_.out_dir);
  }

  void finish(std::size_t k, const RunOutcome& outcome) {
    outcomes_[k] = outcome;
    results_[k] = results_of(k);
    write_summary();  // after every run: a killed sweep keeps the rows it finished
    announce(k, "");
  }

  /// The run's line: how it ended, how far it got.
  void announce(std::size_t k, const char* how_kept) const {
    const RunOutcome& outcome = *outcomes_[k];
    const std::string how = outcome.exit_code == kExitSuccess     ? "done"
                            : outcome.exit_code == kExitNumerical ? "numerical failure (exit 3)"
                            : outcome.exit_code == kExitInterrupted
                                ? "interrupted by " + outcome.signal + " (exit 4)"
                                : fmt::format("ended with exit status {}", outcome.exit_code);
    std::cerr << fmt::format("[{}/{}] {}: {}{} after {} steps, t = {:.4e} s, {:.1f} s wall\n",
                             k + 1, n_, runs_[k].folder, how, how_kept, outcome.steps, outcome.time,
                             outcome.wall_seconds);
  }

  /// `dustlift run` of run k: a fresh run of its scene, or its checkpoint's continuation.
  std::vector<std::string> arguments(std::size_t k) const {
    std::vector<std::string> args{setup_.executable, "run"};
    if (!restart_from_[k].empty()) {
      args.insert(args.end(), {"--restart", restart_from_[k]});
    } else {
      args.push_back(setup_.sweep->scene_path);
      for (const std::string& o : setup_.sweep->overrides) args.insert(args.end(), {"--set", o});
      for (const auto& [key, value] : runs_[k].overrides)
        args.insert(args.end(), {"--set", key + "=" + value});
      args.insert(args.end(), {"--out", folder_of(k), "--overwrite"});
    }
    args.insert(args.end(), {"--threads", std::to_string(setup_.threads_per_run)});
    return args;
  }

  void start_runs() {
    while (!InterruptHandler::requested() &&
           running_.size() < static_cast<std::size_t>(setup_.jobs)) {
      while (next_ < n_ && outcomes_[next_]) ++next_;
      if (next_ == n_) return;
      const std::size_t k = next_++;
      running_.push_back(Child{k, spawn(arguments(k)), Clock::now(), false});
      std::cerr << fmt::format(
          "[{}/{}] {}: {} ({} thread{})\n", k + 1, n_, runs_[k].folder,
          restart_from_[k].empty() ? "started" : "continued from its checkpoint",
          setup_.threads_per_run, setup_.threads_per_run == 1 ? "" : "s");
    }
  }

  void forward_stop() {
    for (Child& c : running_) {
      if (!c.told_to_stop) kill(c.pid, SIGINT);  // the child counts a second one as the same
      c.told_to_stop = true;
    }
  }

  /// The children that ended: their outcome from their log, their row in the summary.
  void reap_ended() {
    for (std::size_t r = 0; r < running_.size();) {
      int wait_status = 0;
      if (waitpid(running_[r].pid, &wait_status, WNOHANG) != running_[r].pid) {
        ++r;
        continue;
      }
      const Child c = running_[r];
      running_.erase(running_.begin() + static_cast<std::ptrdiff_t>(r));
      const int code =
          WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : 128 + WTERMSIG(wait_status);
      RunOutcome outcome = read_earlier_run(folder_of(c.index)).outcome;
      outcome.exit_code = code;
      // The time loop's wall time as the run logged it (what a run one after another reports),
      // else the process's.
      if (code != kExitSuccess || !(outcome.wall_seconds > 0.0))
        outcome.wall_seconds = std::chrono::duration<double>(Clock::now() - c.started).count();
      if (code == kExitSuccess) finished_walls_.push_back(outcome.wall_seconds);
      finish(c.index, outcome);
      if (code != kExitSuccess && status_ != kExitInterrupted) status_ = code;
      if (code == kExitInterrupted)
        std::cerr << fmt::format(
            "continue that run with: dustlift sweep ... --resume (or dustlift run --restart "
            "{})\n",
            outcome.checkpoint);
    }
  }

  /// Every 10 s: each running run's progress and the whole sweep's remaining time.
  void report_progress() {
    if (Clock::now() - last_report_ < std::chrono::seconds(10) || running_.empty()) return;
    last_report_ = Clock::now();
    std::vector<std::pair<double, double>> elapsed_fraction;
    std::string parts;
    for (const Child& c : running_) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - c.started).count();
      const double fraction = progress_fraction(folder_of(c.index)).value_or(0.0);
      elapsed_fraction.emplace_back(elapsed, fraction);
      parts += fmt::format("{}{} {:.0f}%", parts.empty() ? "" : ", ", runs_[c.index].folder,
                           100.0 * fraction);
    }
    std::size_t queued = 0, done = 0;
    for (std::size_t k = 0; k < n_; ++k) {
      done += outcomes_[k] ? 1 : 0;
      queued += k >= next_ && !outcomes_[k] ? 1 : 0;
    }
    std::cerr << fmt::format(
        "sweep: {}/{} done, running {}; sweep ETA {}\n", done, n_, parts,
        format_duration(sweep_eta(finished_walls_, elapsed_fraction, queued, setup_.jobs)));
  }

  const SweepJobsSetup& setup_;
  const std::vector<SweepRun>& runs_;
  const std::vector<Scene>& scenes_;
  std::size_t n_;
  std::vector<std::optional<RunOutcome>> outcomes_;
  std::vector<RunResults> results_;
  std::vector<std::string> restart_from_;
  std::vector<double> finished_walls_;
  std::vector<Child> running_;
  std::size_t next_ = 0;
  int status_ = kExitSuccess;
  Clock::time_point last_report_ = Clock::now();
};

}  // namespace

int run_sweep_jobs(const SweepJobsSetup& setup) {
  return SweepJobs(setup).run();
}

}  // namespace dustlift
