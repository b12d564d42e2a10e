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
std::string mpirun(int ranks) {
  // Root is allowed in CI containers; the ranks even on a busy machine.
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
         "OMPI_MCA_btl_vader_single_copy_mechanism=none " +
         std::string(DUSTLIFT_TEST_MPIEXEC) + " -np " + std::to_string(ranks) +
         " --oversubscribe " + DUSTLIFT_BINARY;
}
std::string mpirun2() {
  return mpirun(2);
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

/// Every array of two checkpoints that differs in any bit: all groups, or with `state_only`
/// the run's state (gas, run, parcels, dem, coupling) without the in-situ outputs' series.
/// Not compared: coupling/rest_reference, the reference state of the resting-parcel skip,
/// which a run on several ranks does not use (it steps every parcel; skipping changes no bit).
std::string differing_anywhere(const Snapshot& a, const Snapshot& b, bool state_only = false) {
  std::string names;
  auto compare = [&](const auto& ma, const auto& mb) {
    for (const auto& [key, v] : ma) {
      if (key == "coupling/rest_reference" || (state_only && key.rfind("insitu/", 0) == 0))
        continue;
      const auto it = mb.find(key);
      const bool same =
          it != mb.end() && it->second.size() == v.size() &&
          (v.empty() || std::memcmp(v.data(), it->second.data(), v.size() * sizeof(v[0])) == 0);
      if (!same) names += key + " ";
    }
  };
  compare(a.f64, b.f64);
  compare(a.i64, b.i64);
  compare(a.i32, b.i32);
  compare(a.i8, b.i8);
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
  EXPECT_EQ(differing_anywhere(dustlift::read_checkpoint((dir / "one" / "checkpoint.h5").string()),
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
  EXPECT_EQ(differing_anywhere(dustlift::read_checkpoint((dir / "one" / "checkpoint.h5").string()),
                               dustlift::read_checkpoint((dir / "rest" / "checkpoint.h5").string()),
                               true),
            "");
  fs::remove_all(dir);
#endif
}

TEST(MpiCli, ADustSceneOnTwoRanksWritesWhatOneRankWritesAndRestartsEitherWay) {
#ifndef DUSTLIFT_TEST_MPIEXEC
  GTEST_SKIP() << "built without MPI";
#else
  // The quickstart on a 30 mm channel over a 15 mm layer (~2,200 parcels), cut inside the
  // layer; to 40 us (the shock past the cut), outputs (VTK, series, checkpoints) every 20 us,
  // and the paper's two force bands moved onto this layer.
  const auto dir = fresh_dir("mpi_cli_dust");
  const std::string scene = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";
  const std::string common =
      " --threads 1 --set run.end_time=4e-5 --set output.interval=2e-5 --set grid.x.start=-0.010"
      " --set grid.x.end=0.020 --set grid.x.cells_below=10 --set grid.y.end=0.008"
      " --set grid.y.uniform_end=0.006 --set grid.y.cells_above=4 --set particles.layer.x_max=0.015"
      // Force bands across the cut (x = 7.5 mm): sampled every step from the band parcels
      // alone, which is all rank 0 gathers then.
      " --set 'output.bands=[{name=\"surface\", x_min=0.004, x_max=0.011, y_min=-0.0001, "
      "y_max=0.0},"
      " {name=\"middle\", x_min=0.004, x_max=0.011, y_min=-0.0011, y_max=-0.0009}]'";
  auto r = run_command(std::string(DUSTLIFT_BINARY) + " run " + scene + " --out " +
                       (dir / "one").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_command(mpirun2() + " run " + scene + " --out " + (dir / "two").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Snapshot one = dustlift::read_checkpoint((dir / "one" / "checkpoint.h5").string());
  EXPECT_EQ(
      differing_anywhere(one, dustlift::read_checkpoint((dir / "two" / "checkpoint.h5").string())),
      "");
  // Three ranks: the middle one has a neighbour on each side (slabs of 17, 16, 17 columns).
  r = run_command(mpirun(3) + " run " + scene + " --out " + (dir / "three").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(differing_anywhere(
                one, dustlift::read_checkpoint((dir / "three" / "checkpoint.h5").string())),
            "");
  // Every series file byte for byte, every gas and parcel file but for its provenance (the command
  // line names another folder).
  const auto without_command_line = [](std::string text) {
    const std::size_t at = text.find("Name=\"command_line\"");
    if (at != std::string::npos) text.erase(at, text.find("</Array>", at) - at);
    return text;
  };
  int files = 0;
  for (const auto& sub : {"series", "vtk"}) {
    if (!fs::exists(dir / "one" / sub)) continue;
    for (const auto& e : fs::directory_iterator(dir / "one" / sub)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".csv" && ext != ".vtp" && ext != ".vtr") continue;
      ++files;
      EXPECT_EQ(without_command_line(read_all(e.path())),
                without_command_line(read_all(dir / "two" / sub / e.path().filename())))
          << e.path().filename();
    }
  }
  EXPECT_GE(files, 3);
  // The surface band holds parcels: its first row samples some (tau, samples, ...).
  std::istringstream band(read_all(dir / "two" / "series" / "forces_surface.csv"));
  std::string header, row;
  std::getline(band, header);
  std::getline(band, row);
  EXPECT_GT(std::stoi(row.substr(row.find(',') + 1)), 100) << row;
  // Stopped after 60 steps on 2 ranks, continued on 1; stopped on 1, continued on 2.
  for (const auto& [first, then] : {std::pair{mpirun2(), std::string(DUSTLIFT_BINARY)},
                                    std::pair{std::string(DUSTLIFT_BINARY), mpirun2()}}) {
    fs::remove_all(dir / "part");
    fs::remove_all(dir / "rest");
    r = run_command(first + " run " + scene + " --out " + (dir / "part").string() + common +
                    " --set run.max_steps=60");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = run_command(then + " run --restart " + (dir / "part" / "checkpoint.h5").string() +
                    " --out " + (dir / "rest").string() + " --threads 1 --set run.max_steps=0");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(differing_anywhere(
                  one, dustlift::read_checkpoint((dir / "rest" / "checkpoint.h5").string()), true),
              "")
        << first << " then " << then;
  }
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
  // Only `run` runs on several ranks.
  r = run_command(mpirun2() + " info " + kShock);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("only `dustlift run`"), std::string::npos) << r.output;
  fs::remove_all(dir);
#endif
}

}  // namespace
