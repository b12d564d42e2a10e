// How OpenMP threads wait (solver/core/wait_policy.hpp): the default is set only where the
// user chose nothing, and the dustlift program runs with it and says so in run.log.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "solver/core/wait_policy.hpp"
#include "support/run_cli.hpp"

using namespace dustlift;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_command;

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? v : "(unset)";
}

}  // namespace

TEST(WaitPolicy, DefaultIsPassiveAfterAShortSpinWhenTheUserChoseNothing) {
  unsetenv("OMP_WAIT_POLICY");
  unsetenv("GOMP_SPINCOUNT");
  EXPECT_TRUE(set_default_wait_policy());
  EXPECT_EQ(env("OMP_WAIT_POLICY"), "passive");
  EXPECT_EQ(env("GOMP_SPINCOUNT"), kDefaultSpinCount);
  EXPECT_FALSE(set_default_wait_policy()) << "set once: a restart does not restart again";
  EXPECT_EQ(
      wait_policy_description(),
      std::string("OpenMP wait: OMP_WAIT_POLICY=passive, GOMP_SPINCOUNT=") + kDefaultSpinCount);
}

TEST(WaitPolicy, AUsersChoiceOfEitherVariableIsKept) {
  unsetenv("GOMP_SPINCOUNT");
  setenv("OMP_WAIT_POLICY", "active", 1);
  EXPECT_FALSE(set_default_wait_policy());
  EXPECT_EQ(env("OMP_WAIT_POLICY"), "active");
  EXPECT_EQ(env("GOMP_SPINCOUNT"), "(unset)");
  unsetenv("OMP_WAIT_POLICY");
  setenv("GOMP_SPINCOUNT", "0", 1);
  EXPECT_FALSE(set_default_wait_policy());
  EXPECT_EQ(env("OMP_WAIT_POLICY"), "(unset)");
  EXPECT_EQ(env("GOMP_SPINCOUNT"), "0");
  unsetenv("GOMP_SPINCOUNT");
}

TEST(WaitPolicy, TheProgramRunsWithTheDefaultOrTheUsersChoiceAndLogsIt) {
  const auto dir = fresh_dir("wait_policy");
  const std::string sod = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/sod.toml";
  const std::string run =
      std::string(DUSTLIFT_BINARY) + " run " + sod + " --set grid.x.cells=50 --threads 2 --out ";
  auto log_of = [](const std::filesystem::path& d) {
    std::ifstream f(d / "run.log");
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  auto r =
      run_command("env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT " + run + (dir / "default").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(log_of(dir / "default")
                .find(std::string("OMP_WAIT_POLICY=passive, GOMP_SPINCOUNT=") + kDefaultSpinCount),
            std::string::npos)
      << log_of(dir / "default");
  r = run_command("env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=passive " + run +
                  (dir / "passive").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(log_of(dir / "passive").find("OMP_WAIT_POLICY=passive, GOMP_SPINCOUNT=(unset)"),
            std::string::npos)
      << log_of(dir / "passive");
  std::filesystem::remove_all(dir);
}
