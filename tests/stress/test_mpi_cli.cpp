// `mpirun -np 2 dustlift run SCENE` end to end (issue 12): the same files as one rank, a
// checkpoint that continues on one rank, bad input reported once.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "insitu/checkpoint.hpp"
#include "support/run_cli.hpp"

namespace fs = std::filesystem;
using dustlift::Snapshot;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_command;

namespace {

#ifdef DUSTLIFT_TEST_MPIEXEC
std::string mpirun2() {
  // Root is allowed in CI containers; two ranks even on a busy machine.
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
         "OMPI_MCA_btl_vader_single_copy_mechanism=none " +
         std::string(DUSTLIFT_TEST_MPIEXEC) + " -np 2 --oversubscribe " + DUSTLIFT_BINARY;
}
#endif

const std::string kShock =
    std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/shock_mach144.toml";

std::string read_all(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// Gas and run arrays that differ in any bit.
std::string differing(const Snapshot& a, const Snapshot& b) {
  std::string names;
  for (const auto& [key, v] : a.f64) {
    const auto it = b.f64.find(key);
    const bool same = it != b.f64.end() && it->second.size() == v.size() &&
                      std::memcmp(v.data(), it->second.data(), v.size() * sizeof(double)) == 0;
    if (!same && (key.rfind("gas/", 0) == 0 || key.rfind("run/", 0) == 0)) names += key + " ";
  }
  return names;
}

TEST(MpiCli, TwoRanksWriteWhatOneRankWrites) {
#ifndef DUSTLIFT_TEST_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  const auto dir = fresh_dir("mpi_cli");
  const std::string common = " --threads 1 --set run.end_time=1e-4 --set output.interval=5e-5";
  auto r = run_command(std::string(DUSTLIFT_BINARY) + " run " + kShock + " --out " +
                       (dir / "one").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_command(mpirun2() + " run " + kShock + " --out " + (dir / "two").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(read_all(dir / "two" / "run.log").find("on 2 ranks, x-slabs of 600, 600 columns"),
            std::string::npos);
  EXPECT_EQ(differing(dustlift::read_checkpoint((dir / "one" / "checkpoint.h5").string()),
                      dustlift::read_checkpoint((dir / "two" / "checkpoint.h5").string())),
            "");
  // Every series file byte for byte (the gas fields rank 0 gathered).
  int series = 0;
  for (const auto& e : fs::directory_iterator(dir / "one" / "series")) {
    if (e.path().extension() != ".csv") continue;
    ++series;
    EXPECT_EQ(read_all(e.path()), read_all(dir / "two" / "series" / e.path().filename()))
        << e.path().filename();
  }
  EXPECT_GE(series, 1);
  // A 2-rank run stopped at step 200 continues on one rank to the same end, bit for bit.
  r = run_command(mpirun2() + " run " + kShock + " --out " + (dir / "part").string() + common +
                  " --set run.max_steps=200");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_command(std::string(DUSTLIFT_BINARY) + " run --restart " +
                  (dir / "part" / "checkpoint.h5").string() + " --out " + (dir / "rest").string() +
                  " --threads 2 --set run.max_steps=0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(differing(dustlift::read_checkpoint((dir / "one" / "checkpoint.h5").string()),
                      dustlift::read_checkpoint((dir / "rest" / "checkpoint.h5").string())),
            "");
  fs::remove_all(dir);
#endif
}

TEST(MpiCli, BadInputOnTwoRanksIsReportedOnceAndWritesNothing) {
#ifndef DUSTLIFT_TEST_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  const auto dir = fresh_dir("mpi_cli_bad");
  auto r = run_command(mpirun2() + " run " + kShock + " --out " + (dir / "out").string() +
                       " --set gas.scheme.cfl=7");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::size_t first = r.output.find("dustlift: error:");
  ASSERT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("dustlift: error:", first + 1), std::string::npos) << "reported twice:\n"
                                                                             << r.output;
  EXPECT_NE(r.output.find("gas.scheme.cfl"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // Particles are not decomposed yet: a clear refusal, not a wrong run.
  r = run_command(mpirun2() + " run " + std::string(DUSTLIFT_SOURCE_DIR) +
                  "/cases/quickstart.toml --out " + (dir / "dust").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("[particles] on 2 MPI ranks"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "dust"));
  // Only `run` runs on several ranks.
  r = run_command(mpirun2() + " info " + kShock);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("only `dustlift run`"), std::string::npos) << r.output;
  fs::remove_all(dir);
#endif
}

}  // namespace
