// A study that uses the machine: `dustlift sweep --jobs 2` runs its runs side by side and gives
// the same bits as one after another; a sweep stopped by SIGINT resumes with --resume, keeps
// what finished, continues what was interrupted from its checkpoint and ends with the outputs
// of the sweep that was never stopped.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "insitu/checkpoint.hpp"
#include "solver/app/run_scene.hpp"
#include "solver/app/sweep_jobs.hpp"
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

const char* kVary = " --vary particles.contact.damping=1e-4,2e-4,3e-4";
const char* kRuns[] = {"particles.contact.damping=1e-4", "particles.contact.damping=2e-4",
                       "particles.contact.damping=3e-4"};

std::vector<std::vector<std::string>> csv_rows(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> row;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');) row.push_back(field);
    rows.push_back(row);
  }
  return rows;
}

/// The summaries agree in every column but the wall time, and every run's final state and
/// series agree bit for bit.
void expect_same_sweep(const fs::path& a, const fs::path& b) {
  const auto ra = csv_rows(a / "summary.csv"), rb = csv_rows(b / "summary.csv");
  ASSERT_EQ(ra.size(), 4u);
  ASSERT_EQ(rb.size(), ra.size());
  std::size_t wall = 0;
  while (wall < ra[0].size() && ra[0][wall] != "wall_time_s") ++wall;
  ASSERT_LT(wall, ra[0].size());
  for (std::size_t r = 0; r < ra.size(); ++r) {
    ASSERT_EQ(ra[r].size(), rb[r].size());
    for (std::size_t c = 0; c < ra[r].size(); ++c) {
      if (c == wall) continue;
      EXPECT_EQ(ra[r][c], rb[r][c]) << "row " << r << " column " << ra[0][c];
    }
  }
  for (const char* run : kRuns) {
    SCOPED_TRACE(run);
    expect_bitwise_equal(read_checkpoint((a / run / "checkpoint.h5").string()),
                         read_checkpoint((b / run / "checkpoint.h5").string()));
    for (const auto& f : fs::directory_iterator(a / run / "series")) {
      if (f.path().extension() != ".csv") continue;
      EXPECT_EQ(read_bytes(f.path()), read_bytes(b / run / "series" / f.path().filename()))
          << f.path().filename();
    }
  }
}

class SweepJobs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    scene_ = dir_ / "mini.toml";
    write_file(scene_, kShockOverDust);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string sweep(const fs::path& out, const std::string& extra) const {
    return "sweep " + scene_.string() + kVary + " --out " + out.string() + extra;
  }
  fs::path dir_, scene_;
};

}  // namespace

TEST_F(SweepJobs, SideBySideRunsEqualTheRunsOneAfterAnother) {
  const auto one = run_cli(sweep(dir_ / "one", " --threads 2"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto two = run_cli(sweep(dir_ / "two", " --jobs 2 --threads 1"));
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_NE(two.output.find("3 runs, 2 side by side with 1 thread each"), std::string::npos)
      << two.output;
  expect_same_sweep(dir_ / "one", dir_ / "two");

  // Resuming a finished sweep runs nothing and keeps every row.
  const auto again = run_cli(sweep(dir_ / "two", " --jobs 2 --resume"));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.output.find("started"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("[3/3] particles.contact.damping=3e-4: done (kept from the earlier "
                              "sweep)"),
            std::string::npos)
      << again.output;
  expect_same_sweep(dir_ / "one", dir_ / "two");

  // A resumed folder must hold this sweep's runs; --resume and --overwrite exclude each other.
  const auto other =
      run_cli("sweep " + scene_.string() +
              " --set run.end_time=1e-5 --vary particles.contact.damping=1e-4 --out " +
              (dir_ / "two").string() + " --resume");
  EXPECT_EQ(other.exit_code, kExitBadInput) << other.output;
  EXPECT_NE(other.output.find("holds a run of another scene"), std::string::npos) << other.output;
  const auto both = run_cli(sweep(dir_ / "two", " --resume --overwrite"));
  EXPECT_EQ(both.exit_code, kExitBadInput) << both.output;
}

TEST_F(SweepJobs, AStoppedSweepResumesToTheOutputsOfTheUninterruptedOne) {
  // Outputs every microsecond make each run long enough to be stopped in the middle.
  const std::string outputs = " --set output.interval=1e-6";
  const auto reference = run_cli(sweep(dir_ / "reference", " --threads 2" + outputs));
  ASSERT_EQ(reference.exit_code, 0) << reference.output;

  const fs::path out = dir_ / "stopped";
  const std::string log = (dir_ / "sweep.txt").string();
  const pid_t child = dustlift::testing::start_cli(
      {"sweep", scene_.string(), "--vary", "particles.contact.damping=1e-4,2e-4,3e-4", "--set",
       "output.interval=1e-6", "--out", out.string(), "--jobs", "2", "--threads", "1"},
      log);
  ASSERT_GT(child, 0);
  // Once the first two runs have both written a few outputs.
  const auto listed = [&](const char* run) {
    const std::string pvd = read_bytes(out / run / "gas.pvd");
    std::size_t n = 0;
    for (std::size_t p = pvd.find("<DataSet"); p != std::string::npos;
         p = pvd.find("<DataSet", p + 1))
      ++n;
    return n;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline &&
         (listed(kRuns[0]) < 4 || listed(kRuns[1]) < 4))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(kill(child, SIGINT), 0);
  int status = 0;
  waitpid(child, &status, 0);
  const std::string said = read_bytes(log);
  ASSERT_TRUE(WIFEXITED(status)) << said;
  EXPECT_EQ(WEXITSTATUS(status), kExitInterrupted) << said;
  EXPECT_NE(said.find("interrupted by SIGINT (exit 4)"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(out / kRuns[2])) << "no run is started after the stop\n" << said;
  const auto stopped = csv_rows(out / "summary.csv");
  ASSERT_GE(stopped.size(), 2u) << said;

  const auto resumed = run_cli(sweep(out, " --jobs 2 --threads 1 --resume" + outputs));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("continued from its checkpoint"), std::string::npos)
      << resumed.output;
  expect_same_sweep(dir_ / "reference", out);
}

TEST(SweepJobsParts, TheLogSaysHowAnEarlierRunEndedAndTheEtaAddsUp) {
  const fs::path dir = fresh_dir("sweep_jobs_parts");
  write_file(dir / "run.log",
             "dustlift run x -> y (1 threads)\n"
             "t = 3.8509e-05 s ( 12.8%)  step 160  dt = 2.146e-07 s  wall 2s  ETA 14s\n");
  EXPECT_EQ(read_earlier_run(dir.string()).state, EarlierRun::Broken);
  EXPECT_DOUBLE_EQ(*progress_fraction(dir.string()), 0.128);
  write_file(dir / "run.log",
             "t = 3.8509e-05 s ( 12.8%)  step 160  dt = 2.146e-07 s  wall 2s  ETA 14s\n"
             "dustlift: numerical failure: step 161: density -1 in cell (3, 4)\n");
  const EarlierRunState failed = read_earlier_run(dir.string());
  EXPECT_EQ(failed.state, EarlierRun::Failed);
  EXPECT_EQ(failed.outcome.exit_code, kExitNumerical);
  EXPECT_EQ(failed.outcome.steps, 160);
  write_file(dir / "run.log", "done: t = 6.883898e-05 s after 300 steps in 4.01 s wall\n");
  const EarlierRunState done = read_earlier_run(dir.string());
  EXPECT_EQ(done.state, EarlierRun::Finished);
  EXPECT_EQ(done.outcome.steps, 300);
  EXPECT_DOUBLE_EQ(done.outcome.wall_seconds, 4.01);
  // Interrupted without a checkpoint to continue from: run again.
  write_file(dir / "run.log",
             "dustlift: interrupted by SIGINT at t = 1e-05 s after 40 steps; checkpoint written\n");
  EXPECT_EQ(read_earlier_run(dir.string()).state, EarlierRun::Broken);
  fs::remove_all(dir);

  // Two finished runs of 10 s, one running at 25 % after 5 s (20 s in all, 15 s to go), two
  // not started (the mean of 10, 10 and 20 s each): (15 + 2 x 40/3) / 2 jobs.
  EXPECT_NEAR(sweep_eta({10.0, 10.0}, {{5.0, 0.25}}, 2, 2), (15.0 + 2.0 * 40.0 / 3.0) / 2.0, 1e-12);
  EXPECT_TRUE(std::isnan(sweep_eta({}, {{1.0, 0.0}}, 3, 2)));
  EXPECT_EQ(threads_per_job(2, 2), 1);
  EXPECT_EQ(threads_per_job(3, 2), 1);
  EXPECT_EQ(threads_per_job(1, 4), 1);
  EXPECT_EQ(threads_per_job(8, 2), 4);
}
