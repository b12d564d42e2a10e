// A long run a researcher can trust: interrupted by SIGINT/SIGTERM (between steps,
// during an output, from outside at any moment), restarted from its final checkpoint to a
// later end, or restarted from a mid-run checkpoint into a folder that already holds later
// outputs, the run ends with the same state, the same .pvd collections and the same series
// (band averages included) as the run that was never interrupted: compared bit for bit.
// Two signals a few milliseconds apart (a process and its group) are one stop request; a
// signal after kStopSignalWindow ends the run at once.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <thread>

#include "insitu/checkpoint.hpp"
#include "solver/app/interrupt.hpp"
#include "solver/app/run_scene.hpp"
#include "solver/scene/scene.hpp"
#include "support/run_cli.hpp"
#include "support/shock_over_dust.hpp"
#include "support/snapshot_compare.hpp"

namespace fs = std::filesystem;
using namespace dustlift;
using dustlift::testing::expect_bitwise_equal;
using dustlift::testing::fresh_dir;
using dustlift::testing::kShockOverDust;
using dustlift::testing::read_bytes;
using dustlift::testing::run_cli;
using dustlift::testing::write_file;

namespace {

struct Entry {
  std::string time, file;
};

std::vector<Entry> pvd_entries(const fs::path& pvd) {
  const std::string text = read_bytes(pvd);
  const std::regex entry(R"re(timestep="([^"]+)" part="0" file="([^"]+)")re");
  std::vector<Entry> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry);
       it != std::sregex_iterator(); ++it)
    found.push_back({(*it)[1].str(), (*it)[2].str()});
  return found;
}

/// One consistent collection: every listed file exists, every numbered file of that kind is
/// listed, times strictly increase, nothing half-written (.tmp) is left.
void expect_consistent_collection(const fs::path& dir, const std::string& prefix) {
  const auto entries = pvd_entries(dir / (prefix + ".pvd"));
  ASSERT_FALSE(entries.empty()) << dir << " " << prefix;
  std::set<std::string> listed;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    EXPECT_TRUE(fs::exists(dir / entries[k].file)) << entries[k].file;
    EXPECT_GT(fs::file_size(dir / entries[k].file), 1000u) << entries[k].file;
    listed.insert(fs::path(entries[k].file).filename().string());
    if (k > 0) {
      EXPECT_LT(std::stod(entries[k - 1].time), std::stod(entries[k].time))
          << prefix << " entry " << k;
    }
  }
  for (const auto& f : fs::directory_iterator(dir / "vtk")) {
    const std::string name = f.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "half-written file left: " << name;
    if (name.rfind(prefix + "_", 0) == 0) {
      EXPECT_TRUE(listed.count(name)) << name << " is not listed in " << prefix << ".pvd";
    }
  }
  EXPECT_FALSE(fs::exists(dir / (prefix + ".pvd.tmp")));
}

/// The same run, bit for bit: every array of the final checkpoints (gas, parcels, contact
/// history, coupling and the observers' series and filter sums), both .pvd collections and
/// every series CSV file byte for byte.
void expect_same_run(const fs::path& reference, const fs::path& continued) {
  const Snapshot a = read_checkpoint((reference / "checkpoint.h5").string());
  const Snapshot b = read_checkpoint((continued / "checkpoint.h5").string());
  expect_bitwise_equal(a, b);
  EXPECT_EQ(a.i64.size(), b.i64.size());
  const auto insitu_arrays = std::count_if(
      a.f64.begin(), a.f64.end(), [](const auto& e) { return e.first.rfind("insitu/", 0) == 0; });
  EXPECT_GT(insitu_arrays, 40) << "the observers' state is in the checkpoint";
  for (const char* pvd : {"gas.pvd", "parcels.pvd"})
    EXPECT_EQ(read_bytes(reference / pvd), read_bytes(continued / pvd)) << pvd;
  std::size_t files = 0;
  for (const auto& f : fs::directory_iterator(reference / "series")) {
    if (f.path().extension() != ".csv") continue;
    ++files;
    EXPECT_EQ(read_bytes(f.path()), read_bytes(continued / "series" / f.path().filename()))
        << f.path().filename();
  }
  // Shock, surface (2), near layer, two bands, probes, dust cloud, its histogram and entrainment.
  EXPECT_EQ(files, 10u);
  expect_consistent_collection(continued, "gas");
  expect_consistent_collection(continued, "parcels");
}

/// Rows of a band series whose bin holds samples (the comparison is not vacuous).
std::size_t band_rows(const fs::path& dir) {
  std::ifstream in(dir / "series" / "forces_surface.csv");
  std::string line;
  std::size_t rows = 0;
  std::getline(in, line);
  while (std::getline(in, line)) ++rows;
  return rows;
}

class InterruptRestart : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    scene_ = dir_ / "mini.toml";
    write_file(scene_, kShockOverDust);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  /// The run never interrupted, into `name`.
  fs::path reference(const std::string& name, const std::string& extra = "") {
    const fs::path out = dir_ / name;
    const auto r =
        run_cli("run " + scene_.string() + " --out " + out.string() + " --threads 2" + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return out;
  }
  /// The scene run in-process into `out`, SIGINT raised `count` times (`pause` apart) in
  /// the output at t = 10 us.
  RunOutcome run_raising_sigint(const fs::path& out, int count,
                                std::chrono::milliseconds pause = std::chrono::milliseconds(0));
  fs::path dir_, scene_;
};

/// An observer that raises `signal` (count times, `pause` apart) in the output of the given
/// index; added before the writers, so the signal arrives while that output is being written.
class RaiseDuringOutput final : public Observer {
 public:
  RaiseDuringOutput(int output, int signal, int count,
                    std::chrono::milliseconds pause = std::chrono::milliseconds(0))
      : output_(output), signal_(signal), count_(count), pause_(pause) {}
  void on_start(const StateView&) override {}
  void on_output(const StateView&) override {
    if (++outputs_ != output_) return;
    for (int k = 0; k < count_; ++k) {
      if (k > 0) std::this_thread::sleep_for(pause_);
      raise(signal_);
    }
  }

 private:
  int output_, signal_, count_, outputs_ = 0;
  std::chrono::milliseconds pause_;
};

RunOutcome InterruptRestart::run_raising_sigint(const fs::path& out, int count,
                                                std::chrono::milliseconds pause) {
  const Scene scene = parse_scene(kShockOverDust, scene_.string());
  RunOptions options;
  options.echo_log = false;
  options.scene_label = scene_.string();
  options.extra_observers = [count, pause] {
    std::vector<std::unique_ptr<Observer>> v;
    v.push_back(
        std::make_unique<RaiseDuringOutput>(2, SIGINT, count, pause));  // the output at t = 10 us
    return v;
  };
  return run_scene(scene, out.string(), options);
}

}  // namespace

TEST_F(InterruptRestart, ExtensionFromTheFinalCheckpointEqualsTheUninterruptedRun) {
  const fs::path full = reference("full");
  // What once failed: extended from its end (an output time), the run once stopped with a
  // zero time step, or took a 1e-20 s step to an output time rounded differently.
  const fs::path part = dir_ / "part";
  auto r = run_cli("run " + scene_.string() + " --out " + part.string() +
                   " --threads 2 --set run.end_time=5e-6");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Snapshot first_end = read_checkpoint((part / "checkpoint.h5").string());
  EXPECT_EQ(first_end.f64.at("run/time")[0], 5e-6) << "the end time is reached exactly";
  r = run_cli("run --restart " + (part / "checkpoint.h5").string() +
              " --threads 1 --set run.end_time=1.5e-5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("run --restart " + (part / "checkpoint.h5").string() +
              " --threads 2 --set run.end_time=2e-5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_same_run(full, part);
  EXPECT_GT(band_rows(full), 10u);
  const std::string log = read_bytes(part / "run.log");
  EXPECT_NE(log.find("restarted at t = 1.500000e-05 s"), std::string::npos) << log;
  EXPECT_EQ(pvd_entries(part / "gas.pvd").size(), 5u);  // 0, 5, 10, 15, 20 us: no repeated time
}

TEST_F(InterruptRestart,
       MidRunCheckpointRestartedInAFolderWithLaterOutputsEqualsTheUninterruptedRun) {
  // Checkpoints every 3 us (not output times), and the one of t >= 9 us kept aside as a run
  // killed after it would have left it, while the folder goes on to the end.
  const std::string cadence = " --set output.checkpoint_interval=3e-6";
  const fs::path full = reference("full", cadence);
  const Scene scene =
      parse_scene(kShockOverDust, scene_.string(), {"output.checkpoint_interval=3e-6"});
  const fs::path killed = dir_ / "killed";
  RunOptions options;
  options.echo_log = false;
  options.scene_label = scene_.string();
  struct KeepCheckpoint final : Observer {
    fs::path folder;
    bool kept = false;
    void on_start(const StateView&) override {}
    void on_output(const StateView&) override {}
    void on_step(const StateView& v) override {
      if (kept || v.time < 1.1e-5)
        return;  // the checkpoint of the step at or after 9 us is on disk
      fs::copy_file(folder / "checkpoint.h5", folder.parent_path() / "mid.h5");
      kept = true;
    }
  };
  options.extra_observers = [&] {
    std::vector<std::unique_ptr<Observer>> v;
    auto keep = std::make_unique<KeepCheckpoint>();
    keep->folder = killed;
    v.push_back(std::move(keep));
    return v;
  };
  ASSERT_EQ(run_scene(scene, killed.string(), options).exit_code, kExitSuccess);
  fs::rename(dir_ / "mid.h5", killed / "checkpoint.h5");
  const Snapshot mid = read_checkpoint((killed / "checkpoint.h5").string());
  const double t = mid.f64.at("run/time")[0];
  EXPECT_GE(t, 9e-6);
  EXPECT_LT(t, 1e-5) << "a checkpoint between two outputs";
  EXPECT_TRUE(fs::exists(killed / "vtk" / "gas_000004.vtr"))
      << "outputs after the checkpoint are on disk";
  const auto r = run_cli("run --restart " + (killed / "checkpoint.h5").string() + " --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_same_run(full, killed);
}

TEST_F(InterruptRestart,
       SigintDuringAnOutputFinishesItCheckpointsAndTheRestartEqualsTheUninterruptedRun) {
  const fs::path full = reference("full");
  const fs::path stopped = dir_ / "stopped";
  const RunOutcome outcome = run_raising_sigint(stopped, 1);
  EXPECT_EQ(outcome.exit_code, kExitInterrupted);
  EXPECT_EQ(outcome.signal, "SIGINT");
  EXPECT_EQ(outcome.time, 1e-5) << "stopped after the step of that output";
  const auto entries = pvd_entries(stopped / "gas.pvd");
  ASSERT_EQ(entries.size(), 3u) << "the output in progress was completed";
  EXPECT_EQ(entries.back().time, "1e-05");
  expect_consistent_collection(stopped, "gas");
  expect_consistent_collection(stopped, "parcels");
  EXPECT_EQ(read_checkpoint((stopped / "checkpoint.h5").string()).f64.at("run/time")[0], 1e-5);
  const std::string log = read_bytes(stopped / "run.log");
  EXPECT_NE(log.find("interrupted by SIGINT at t = 1.000000e-05 s"), std::string::npos) << log;
  EXPECT_NE(
      log.find("continue with: dustlift run --restart " + (stopped / "checkpoint.h5").string()),
      std::string::npos);
  const auto r = run_cli("run --restart " + (stopped / "checkpoint.h5").string() + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_same_run(full, stopped);
}

TEST_F(InterruptRestart, SignalsFromOutsideAtAnyMomentThenRestartEqualTheUninterruptedRun) {
  // Outputs every microsecond (most of the run's wall time is spent writing them); each signal
  // is sent as soon as the gas collection lists a frame, i.e. while the parcel file of that
  // output is being written, or the steps after it are being computed.
  const std::string outputs = " --set output.interval=1e-6";
  const fs::path full = reference("full", outputs);
  struct Trial {
    int signal;
    std::size_t after_frames;
  };
  for (const Trial trial : {Trial{SIGINT, 3}, Trial{SIGTERM, 8}, Trial{SIGINT, 14}}) {
    const fs::path out = dir_ / ("stopped_" + std::to_string(trial.after_frames));
    const std::string log = (dir_ / "child.txt").string();
    const pid_t child =
        dustlift::testing::start_cli({"run", scene_.string(), "--out", out.string(), "--threads",
                                      "1", "--set", "output.interval=1e-6"},
                                     log);
    ASSERT_GT(child, 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (
        std::chrono::steady_clock::now() < deadline &&
        (!fs::exists(out / "gas.pvd") || pvd_entries(out / "gas.pvd").size() < trial.after_frames))
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    kill(child, trial.signal);
    int status = 0;
    waitpid(child, &status, 0);
    const std::string said = read_bytes(log);
    ASSERT_TRUE(WIFEXITED(status)) << said;
    EXPECT_EQ(WEXITSTATUS(status), kExitInterrupted) << said;
    EXPECT_NE(
        said.find(std::string("interrupted by ") + (trial.signal == SIGINT ? "SIGINT" : "SIGTERM")),
        std::string::npos)
        << said;
    EXPECT_NE(
        said.find("continue with: dustlift run --restart " + (out / "checkpoint.h5").string()),
        std::string::npos)
        << said;
    expect_consistent_collection(out, "gas");
    expect_consistent_collection(out, "parcels");
    const double stopped_at =
        read_checkpoint((out / "checkpoint.h5").string()).f64.at("run/time")[0];
    EXPECT_LT(stopped_at, 2e-5) << "the signal came before the end";
    std::printf("%s after %zu frames: stopped at t = %.6e s with %zu frames listed\n",
                trial.signal == SIGINT ? "SIGINT" : "SIGTERM", trial.after_frames, stopped_at,
                pvd_entries(out / "gas.pvd").size());
    const auto r = run_cli("run --restart " + (out / "checkpoint.h5").string() + " --threads 2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_same_run(full, out);
  }
}

TEST_F(InterruptRestart, ASecondSignalAfterTheWindowEndsTheRunAtOnce) {
  // The child runs the driver in-process (no OpenMP used in this process before the fork).
  const Scene scene = parse_scene(kShockOverDust, scene_.string());
  const fs::path out = dir_ / "twice";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    RunOptions options;
    options.echo_log = false;
    options.extra_observers = [] {
      std::vector<std::unique_ptr<Observer>> v;
      // The second signal comes after the window in which signals join the first one.
      v.push_back(std::make_unique<RaiseDuringOutput>(
          1, SIGINT, 2, kStopSignalWindow + std::chrono::milliseconds(200)));
      return v;
    };
    run_scene(scene, out.string(), options);
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_EQ(pvd_entries(out / "gas.pvd").size(), 1u)
      << "killed before the output of t = 5 us was listed";
}

TEST_F(InterruptRestart, TwoSignalsTenMillisecondsApartAreOneStopRequestWithACheckpoint) {
  // As `timeout`, `mpirun` and batch systems deliver them: one SIGINT to the process, another
  // to its process group 10 ms later. Both are one stop request: the run finishes its step,
  // writes the checkpoint of the progress since the last output and exits 4.
  const fs::path out = dir_ / "quickstart";
  const std::string log = (dir_ / "child.txt").string();
  // Its own process group, as a job started by a batch system.
  const pid_t child = dustlift::testing::start_cli(
      {"run", std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml", "--out", out.string(),
       "--threads", "2"},
      log, true);
  ASSERT_GT(child, 0);
  // Once the first output after t = 0 is listed and the run has gone on a little beyond it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline &&
         (!fs::exists(out / "gas.pvd") || pvd_entries(out / "gas.pvd").size() < 2))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::size_t listed_before = pvd_entries(out / "gas.pvd").size();
  ASSERT_EQ(kill(child, SIGINT), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(kill(-child, SIGINT), 0);  // the group: the same process again
  int status = 0;
  waitpid(child, &status, 0);
  const std::string said = read_bytes(log);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << "\n" << said;
  EXPECT_EQ(WEXITSTATUS(status), kExitInterrupted) << said;
  EXPECT_NE(said.find("interrupted by SIGINT"), std::string::npos) << said;
  // The log names the joined signal, unless the kernel merged the two (a signal already
  // pending when the next arrives is delivered once: a busy machine may not run the process
  // within the 10 ms).
  const bool joined =
      said.find("1 more signal(s) within 1000 ms of the first counted as the same stop request") !=
      std::string::npos;
  ASSERT_TRUE(fs::exists(out / "checkpoint.h5")) << said;
  const auto entries = pvd_entries(out / "gas.pvd");
  ASSERT_GE(entries.size(), listed_before);
  const double stopped_at = read_checkpoint((out / "checkpoint.h5").string()).f64.at("run/time")[0];
  EXPECT_GE(stopped_at, std::stod(entries.back().time))
      << "the checkpoint holds the progress since the last output";
  EXPECT_LT(stopped_at, 0.3e-3) << "stopped before the end";
  expect_consistent_collection(out, "gas");
  std::printf("two SIGINTs 10 ms apart (%s): stopped at t = %.6e s, last output listed at %s s\n",
              joined ? "handled as two, joined" : "delivered as one", stopped_at,
              entries.back().time.c_str());
}

TEST_F(InterruptRestart, ASignalTenMillisecondsAfterTheFirstJoinsItsStopRequest) {
  // In-process, so that both signals are handled (raise() runs the handler before it returns):
  // the second, 10 ms after the first, joins the first one's stop request.
  const fs::path out = dir_ / "joined";
  const RunOutcome outcome = run_raising_sigint(out, 2, std::chrono::milliseconds(10));
  EXPECT_EQ(outcome.exit_code, kExitInterrupted);
  EXPECT_EQ(outcome.signal, "SIGINT");
  EXPECT_EQ(InterruptHandler::joined_signals(), 1);
  EXPECT_EQ(read_checkpoint((out / "checkpoint.h5").string()).f64.at("run/time")[0], 1e-5);
  const std::string log = read_bytes(out / "run.log");
  EXPECT_NE(log.find("dustlift: 1 more signal(s) within 1000 ms of the first counted as the same "
                     "stop request"),
            std::string::npos)
      << log;
}
