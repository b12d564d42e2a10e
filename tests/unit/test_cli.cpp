// The command line end to end: exit codes, error messages naming the key, no partial output.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkRectilinearGrid.h>
#include <vtkXMLRectilinearGridReader.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "solver/app/info.hpp"
#include "solver/gas/exact_riemann.hpp"
#include "solver/sim/simulation.hpp"
#include "support/run_cli.hpp"

namespace fs = std::filesystem;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_cli;
using dustlift::testing::write_file;

namespace {

const std::string kSod = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/sod.toml";

}  // namespace

TEST(Cli, InfoPrintsEffectsGridAndSteps) {
  const auto r = run_cli("info " + kSod);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("effects on"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("grid: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("estimated steps"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particles: none"), std::string::npos) << r.output;
  // How it runs in parallel: a gas-only scene names mpirun when the build has MPI.
#ifdef DUSTLIFT_TEST_MPIEXEC
  EXPECT_NE(r.output.find("MPI: mpirun -np N dustlift run SCENE"), std::string::npos) << r.output;
#else
  EXPECT_NE(r.output.find("MPI: not in this build"), std::string::npos) << r.output;
#endif
}

TEST(Cli, InfoSaysRanksSplitTheParcelsToo) {
  const auto r = run_cli("info " + std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
#ifdef DUSTLIFT_TEST_MPIEXEC
  EXPECT_NE(r.output.find("each rank with the parcels in its slab"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("for scenes without particles"), std::string::npos) << r.output;
#else
  EXPECT_NE(r.output.find("MPI: not in this build"), std::string::npos) << r.output;
#endif
}

TEST(Cli, InfoAndTheRunLogGiveTheShockSpeedAndThePostShockState) {
  const auto r = run_cli("info " + std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto at = r.output.find("shock: Mach 1.44 along +x at ");
  ASSERT_NE(at, std::string::npos) << r.output;
  // Mach 1.44 into 101 kPa, 300 K air (gamma 1.4 at 300 K): W = 1.44 sqrt(1.4 * 287.1 * 300)
  // = 501 m/s (R = 288.2 J/(kg K) of the O2:N2 = 1:3.76 mixture), p2 = p1 (1 + 2.8 / 2.4 (M^2 - 1))
  // = 227.5 kPa, T2 = 384.2 K (ideal-gas relations;
  // the thermally perfect solve differs by < 0.3 %).
  const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
  double speed = 0, p1 = 0, T1 = 0, p2 = 0, T2 = 0;
  ASSERT_EQ(
      std::sscanf(
          line.c_str(),
          "shock: Mach 1.44 along +x at %lf m/s into %lf kPa, %lf K; behind it %lf kPa, %lf K",
          &speed, &p1, &T1, &p2, &T2),
      5)
      << line;
  EXPECT_NEAR(speed, 501.0, 1.5);
  EXPECT_EQ(p1, 101.0);
  EXPECT_NEAR(p2, 227.5, 0.7);
  EXPECT_NEAR(T2, 384.2, 1.2);
}

TEST(Cli, OneOverrideSwitchesTheDustOff) {
  // The quickstart's [particles], [coupling] and its dust outputs stay as written, unread.
  const auto r = run_cli("info " + std::string(DUSTLIFT_SOURCE_DIR) +
                         "/cases/quickstart.toml --set particles.enabled=false");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("parcels: 0 (gas only)"), std::string::npos) << r.output;
  // Without the switch, a [coupling] section with no [particles] is still refused.
  const auto dir = fresh_dir("dust_off");
  write_file(dir / "s.toml",
             "[run]\nend_time = 1e-5\n[grid.x]\nstart = 0.0\nend = 0.01\ncells = 10\n"
             "[grid.y]\nstart = 0.0\nend = 0.01\ncells = 10\n[initial]\nkind = \"uniform\"\n"
             "state = { p = 1e5, T = 300.0 }\n[coupling]\ndrag = true\n");
  const auto refused = run_cli("info " + (dir / "s.toml").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("needs [particles]"), std::string::npos) << refused.output;
}

TEST(Cli, InfoEstimatesTheStepsOfAShockRunningInFromCoarseInflowCells) {
  // The quickstart's geometry, shortened: the post-shock gas starts in the stretched cells
  // upstream, so the t = 0 step (167 steps) is far longer than the steps once it reaches the
  // 0.5 mm cells (the run takes 259).
  const dustlift::Scene scene =
      dustlift::load_scene(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml",
                           {"grid.x.start=-0.02", "grid.x.end=0.02", "grid.x.cells_below=10",
                            "grid.y.end=0.006", "grid.y.uniform_end=0.004", "grid.y.cells_above=2",
                            "particles.layer.x_max=0.02", "run.end_time=6e-5"});
  dustlift::Simulation sim(scene);
  const double estimate = dustlift::estimated_steps(sim),
               at_t0 = std::ceil(6e-5 / sim.gas().stable_dt());
  sim.run("");
  const double steps = static_cast<double>(sim.step());
  std::printf("steps: %.0f taken, %.0f estimated, %.0f at the t = 0 step\n", steps, estimate,
              at_t0);
  EXPECT_LT(std::abs(estimate - steps), 0.1 * steps);
  EXPECT_GT(std::abs(at_t0 - steps), 0.3 * steps) << "the old estimate, for comparison";
}

TEST(Cli, VersionNamesTheBuild) {
  const auto r = run_cli("--version");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::regex_search(
      r.output, std::regex("^dustlift [0-9]+\\.[0-9]+\\.[0-9]+ \\((git [0-9a-f]|not built)")))
      << r.output;
}

TEST(Cli, AFreshRunRefusesAnOccupiedFolderAndOverwriteReplacesAnEarlierRun) {
  const auto dir = fresh_dir("cli_fresh_folder");
  const std::string run =
      "run " + kSod + " --set grid.x.cells=50 --threads 1 --out " + (dir / "out").string();
  ASSERT_EQ(run_cli(run).exit_code, 0);
  write_file(dir / "out" / "vtk" / "gas_000099.vtr", "stale");  // e.g. from a longer earlier run
  auto r = run_cli(run);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("not empty"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "vtk" / "gas_000099.vtr")) << "nothing touched";
  r = run_cli(run + " --overwrite");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out" / "vtk" / "gas_000099.vtr"))
      << "the earlier run's files are gone";
  // The run says what made it.
  std::ifstream log(dir / "out" / "run.log");
  std::string first, second;
  std::getline(log, first);
  std::getline(log, second);
  EXPECT_EQ(first.rfind("dustlift 0.", 0), 0u) << first;
  EXPECT_NE(second.find("command: "), std::string::npos) << second;
  EXPECT_NE(second.find(" run " + kSod), std::string::npos) << second;
  // --overwrite never empties a folder that holds no dustlift output.
  fs::create_directories(dir / "mine");
  write_file(dir / "mine" / "thesis.tex", "x");
  r = run_cli("run " + kSod + " --out " + (dir / "mine").string() + " --overwrite");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(fs::exists(dir / "mine" / "thesis.tex"));
  fs::remove_all(dir);
}

TEST(Cli, RunWritesResolvedSceneAndGasCollection) {
  const auto dir = fresh_dir("cli_run");
  const auto r =
      run_cli("run " + kSod + " --out " + dir.string() + " --set grid.x.cells=100 --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "scene.resolved.toml"));
  EXPECT_TRUE(fs::exists(dir / "run.log"));
  ASSERT_TRUE(fs::exists(dir / "gas.pvd"));
  // The last dataset of gas.pvd is the final state: t = end_time, and its density is the
  // exact Sod solution to the accuracy of 100 MUSCL-3 cells.
  std::ifstream pvd(dir / "gas.pvd");
  std::stringstream text;
  text << pvd.rdbuf();
  const std::string xml = text.str();
  const std::regex entry(R"re(timestep="([^"]+)"[^>]*file="([^"]+)")re");
  std::string last_file;
  double last_time = -1.0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), entry); it != std::sregex_iterator();
       ++it) {
    last_time = std::stod((*it)[1].str());
    last_file = (*it)[2].str();
  }
  EXPECT_NEAR(last_time, 0.2, 1e-12);
  vtkNew<vtkXMLRectilinearGridReader> reader;
  reader->SetFileName((dir / last_file).string().c_str());
  reader->Update();
  vtkRectilinearGrid* grid = reader->GetOutput();
  ASSERT_EQ(grid->GetNumberOfCells(), 200);  // 100 x 2 cells
  vtkDataArray* rho = grid->GetCellData()->GetArray("density");
  ASSERT_NE(rho, nullptr);
  const dustlift::ExactRiemannSolver exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  double l1 = 0.0;
  for (int i = 0; i < 100; ++i) {
    const double x = (i + 0.5) / 100.0;
    l1 += std::abs(rho->GetTuple1(i) - exact.sample((x - 0.5) / 0.2).rho) / 100.0;
  }
  EXPECT_LT(l1, 1e-2) << "density L1 of the final .vtr against the exact solution";
  fs::remove_all(dir);
}

struct BadScene {
  const char* name;
  const char* overrides;
  const char* key_in_message;
};

class CliBadScene : public ::testing::TestWithParam<BadScene> {};

TEST_P(CliBadScene, ExitsWithCode2NamingTheKeyAndWritesNothing) {
  const auto& p = GetParam();
  const auto dir = fresh_dir(std::string("bad_") + p.name);
  const fs::path out = dir / "out";
  const auto r = run_cli("run " + kSod + " --out " + out.string() + " " + p.overrides);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(p.key_in_message), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "a rejected scene must leave no output folder";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Table, CliBadScene,
    ::testing::Values(BadScene{"unknown_key", "--set run.speed=2", "run.speed"},
                      BadScene{"wrong_type", "--set grid.x.cells=\\\"many\\\"", "grid.x.cells"},
                      BadScene{"negative_size", "--set grid.x.end=-1.0", "grid.x.end"},
                      BadScene{"zero_cells", "--set grid.y.cells=0", "grid.y.cells"},
                      BadScene{"negative_density", "--set initial.left.rho=-1", "initial.left.rho"},
                      BadScene{"bad_cfl", "--set gas.scheme.cfl=1.5", "gas.scheme.cfl"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Cli, MaterialAndLayerMistakesNameTheKeyAndTheBounds) {
  const std::string quickstart = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";
  const auto dir = fresh_dir("bad_material");
  // The layer's downstream end beyond the grid: the key, the grid's edge and its bounds.
  auto r = run_cli("run " + quickstart + " --out " + (dir / "a").string() + " --set particles.layer.x_max=0.5");
  expect_bad_input(r, "particles.layer.x_max", dir / "a", "layer outside");
  EXPECT_NE(r.output.find("grid.x.end = 0.15 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("x in [-0.06, 0.15] m, y in [-0.002, 0.03] m"), std::string::npos) << r.output;
  // A diameter in micrometres: the diameter is named, not the volume fraction.
  r = run_cli("run " + quickstart + " --out " + (dir / "b").string() + " --set particles.diameter=40");
  expect_bad_input(r, "particles.diameter", dir / "b", "diameter in um");
  EXPECT_NE(r.output.find("lengths are in metres"), std::string::npos) << r.output;
  std::ifstream in(quickstart);
  std::stringstream text;
  text << in.rdbuf();
  const std::string no_damping = std::regex_replace(text.str(), std::regex("\\ndamping = [^\\n]*"), "");
  // Both a damping and a restitution: refused, naming the restitution.
  r = run_cli("run " + quickstart + " --out " + (dir / "c").string() + " --set particles.contact.restitution=0.9");
  expect_bad_input(r, "particles.contact.restitution", dir / "c", "damping and restitution");
  // A restitution instead of the damping: it follows for two 100 um particles, and info says so.
  write_file(dir / "restitution.toml", no_damping + "\n");
  r = run_cli("info " + (dir / "restitution.toml").string() + " --set particles.contact.restitution=0.9");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("restitution 0.9 for every pair"), std::string::npos) << r.output;
  // h = -2 ln e sqrt(m_eff k_n) / sqrt(pi^2 + ln^2 e), m_eff = rho pi d^3 / 12.
  const double m_eff = 980.0 * M_PI * 1e-12 / 12.0, l = std::log(0.9);
  const double h = -2.0 * l * std::sqrt(m_eff * 5e4) / std::sqrt(M_PI * M_PI + l * l);
  EXPECT_NE(r.output.find(fmt::format("particles.contact.damping = {}", h)), std::string::npos) << h << "\n" << r.output;
  // Cohesion: the effect list names it with its pull-off force and Bond number; a negative
  // Hamaker constant is refused naming the key.
  r = run_cli("info " + quickstart + " --set particles.cohesion.hamaker=1e-19");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // F_c = A R* / (6 s0^2) with R* = 25 um: 2.604e-6 N; Bond number F_c / (m g) = 517 for 100 um, 980 kg/m^3.
  EXPECT_NE(r.output.find("cohesion: van der Waals per real pair (Hamaker 1e-19 J"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("pull-off force 2.604e-06 N between two particles of 100 um (Bond number F_c/(m g) 517.3 at g = 9.81"),
            std::string::npos)
      << r.output;
  r = run_cli("run " + quickstart + " --out " + (dir / "d").string() + " --set particles.cohesion.hamaker=-1e-19");
  expect_bad_input(r, "particles.cohesion.hamaker", dir / "d", "negative Hamaker constant");
  fs::remove_all(dir);
}

TEST(Cli, UnknownKeyInFileNamesFileAndLine) {
  const auto dir = fresh_dir("bad_file");
  write_file(dir / "s.toml", "[run]\nend_time = 0.1\nspeed = 3\n");
  const auto r = run_cli("run " + (dir / "s.toml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("s.toml:3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run.speed"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(Cli, MissingSceneFileIsBadInput) {
  const auto r = run_cli("run /nonexistent/scene.toml --out /tmp/never");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot open"), std::string::npos) << r.output;
}

TEST(Cli, UnwritableOutputFolderIsBadInput) {
  const auto dir = fresh_dir("unwritable");
  write_file(dir / "file", "x");  // a regular file where a folder is wanted
  const auto r = run_cli("run " + kSod + " --out " + (dir / "file" / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("output folder"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(Cli, NumericalFailureExitsWithCode3NamingStepCellAndVariable) {
  // A density ratio of 1e30 across the diaphragm is beyond what the scheme keeps positive:
  // the run must stop with exit code 3 and say where and what, not crash or write NaNs on.
  const auto dir = fresh_dir("blow_up");
  const auto r = run_cli("run " + kSod + " --out " + dir.string() +
                         " --set \"initial.left={ rho = 1.0, p = 1e6 }\" --set \"initial.right={ "
                         "rho = 1e-30, p = 1e-30 }\"");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("numerical failure: step "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("gas cell (i, j) = ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("is not positive"), std::string::npos) << r.output;
  fs::remove_all(dir);
}
