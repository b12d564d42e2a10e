// `mpirun -np 2 dustlift run SCENE` end to end: the same files as one rank, a
// checkpoint that continues on one rank, bad input reported once.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPRectilinearGridReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLReader.h>
#include <vtkXMLRectilinearGridReader.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
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
/// The resting-parcel skip's reference (coupling/rest_reference) and rest counts included: the
/// ranks agree on the whole grid's.
std::string differing_anywhere(const Snapshot& a, const Snapshot& b, bool state_only = false) {
  std::string names;
  auto compare = [&](const auto& ma, const auto& mb) {
    for (const auto& [key, v] : ma) {
      if (state_only && key.rfind("insitu/", 0) == 0) continue;
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

/// Every value of a VTK array, component by component.
std::vector<double> values_of(vtkDataArray* a) {
  std::vector<double> v;
  if (a == nullptr) return v;
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k)
    for (int c = 0; c < a->GetNumberOfComponents(); ++c) v.push_back(a->GetComponent(k, c));
  return v;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// A file as ParaView reads it: a whole file with `Whole`, a summary of pieces
/// (`parallel_extension`) with `Parallel`.
template <class Data, class Whole, class Parallel>
vtkSmartPointer<Data> read_vtk(const fs::path& p, const char* parallel_extension) {
  vtkSmartPointer<vtkXMLReader> r;
  if (p.extension() == parallel_extension) {
    r = vtkSmartPointer<Parallel>::New();
  } else {
    r = vtkSmartPointer<Whole>::New();
  }
  r->SetFileName(p.string().c_str());
  r->Update();
  return Data::SafeDownCast(r->GetOutputDataObject(0));
}
vtkSmartPointer<vtkRectilinearGrid> read_gas(const fs::path& p) {
  return read_vtk<vtkRectilinearGrid, vtkXMLRectilinearGridReader, vtkXMLPRectilinearGridReader>(
      p, ".pvtr");
}
vtkSmartPointer<vtkPolyData> read_parcels(const fs::path& p) {
  return read_vtk<vtkPolyData, vtkXMLPolyDataReader, vtkXMLPPolyDataReader>(p, ".pvtp");
}

/// The arrays (and coordinates) in which two gas files differ in any bit; "" when alike.
std::string gas_differences(const fs::path& a_path, const fs::path& b_path) {
  const auto a = read_gas(a_path), b = read_gas(b_path);
  if (a->GetNumberOfCells() == 0 || a->GetNumberOfCells() != b->GetNumberOfCells())
    return "cell count ";
  std::string names;
  if (!bitwise_equal(values_of(a->GetXCoordinates()), values_of(b->GetXCoordinates())))
    names += "x ";
  if (!bitwise_equal(values_of(a->GetYCoordinates()), values_of(b->GetYCoordinates())))
    names += "y ";
  if (a->GetCellData()->GetNumberOfArrays() != b->GetCellData()->GetNumberOfArrays())
    names += "array count ";
  for (int k = 0; k < a->GetCellData()->GetNumberOfArrays(); ++k) {
    const char* name = a->GetCellData()->GetArrayName(k);
    if (!bitwise_equal(values_of(a->GetCellData()->GetArray(name)),
                       values_of(b->GetCellData()->GetArray(name))))
      names += std::string(name) + " ";
  }
  return names;
}

/// The same for parcel files, each parcel found by its id (the points' order may differ).
std::string parcel_differences(const fs::path& a_path, const fs::path& b_path) {
  const auto a = read_parcels(a_path), b = read_parcels(b_path);
  if (a->GetNumberOfPoints() == 0 || a->GetNumberOfPoints() != b->GetNumberOfPoints())
    return "point count ";
  const auto by_id = [](vtkPolyData* p) {
    const std::vector<double> id = values_of(p->GetPointData()->GetArray("id"));
    std::vector<std::size_t> order(id.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t i, std::size_t j) { return id[i] < id[j]; });
    return order;
  };
  const std::vector<std::size_t> oa = by_id(a), ob = by_id(b);
  const auto sorted = [](vtkDataArray* array, const std::vector<std::size_t>& order) {
    std::vector<double> v;
    if (array == nullptr) return v;
    for (std::size_t i : order)
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        v.push_back(array->GetComponent(static_cast<vtkIdType>(i), c));
    return v;
  };
  std::string names;
  if (!bitwise_equal(sorted(a->GetPoints()->GetData(), oa), sorted(b->GetPoints()->GetData(), ob)))
    names += "points ";
  if (a->GetNumberOfVerts() != b->GetNumberOfVerts()) names += "vertices ";
  if (a->GetPointData()->GetNumberOfArrays() != b->GetPointData()->GetNumberOfArrays())
    names += "array count ";
  for (int k = 0; k < a->GetPointData()->GetNumberOfArrays(); ++k) {
    const char* name = a->GetPointData()->GetArrayName(k);
    if (!bitwise_equal(sorted(a->GetPointData()->GetArray(name), oa),
                       sorted(b->GetPointData()->GetArray(name), ob)))
      names += std::string(name) + " ";
  }
  return names;
}

/// The files a .pvd lists, in order.
std::vector<fs::path> listed_files(const fs::path& pvd) {
  const std::string text = read_all(pvd);
  std::vector<fs::path> files;
  for (std::size_t at = text.find("file=\""); at != std::string::npos;
       at = text.find("file=\"", at + 1)) {
    const std::size_t start = at + 6;
    files.push_back(pvd.parent_path() / text.substr(start, text.find('"', start) - start));
  }
  return files;
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
  // Skipping within the default tolerance leaves the gas ahead of the shock alone, so the cuts
  // follow the shock (from 600, 600 columns; 200, 1000 at the end, measured).
  EXPECT_NE(read_all(dir / "two" / "run.log").find("on 2 ranks, x-slabs of 200, 1000 columns"),
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
  // Every series file byte for byte.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir / "one" / "series")) {
    if (e.path().extension() != ".csv") continue;
    ++files;
    EXPECT_EQ(read_all(e.path()), read_all(dir / "two" / "series" / e.path().filename()))
        << e.path().filename();
  }
  EXPECT_GE(files, 3);
  // Each rank wrote its piece of every gas and parcel output, rank 0 the .pvtr/.pvtp joining
  // them, which the .pvd lists: read as ParaView reads them, every array equals one rank's
  // file bit for bit (on 3 ranks too: a middle slab with a neighbour on each side).
  for (const char* ranks : {"two", "three"}) {
    for (const auto& [kind, piece_ext] : {std::pair{"gas", ".vtr"}, std::pair{"parcels", ".vtp"}}) {
      const std::vector<fs::path> whole = listed_files(dir / "one" / (std::string(kind) + ".pvd"));
      const std::vector<fs::path> joined = listed_files(dir / ranks / (std::string(kind) + ".pvd"));
      ASSERT_EQ(whole.size(), 3u) << kind;
      ASSERT_EQ(joined.size(), whole.size()) << ranks << " " << kind;
      for (std::size_t k = 0; k < whole.size(); ++k) {
        EXPECT_EQ(joined[k].extension(), std::string(".p") + (piece_ext + 1)) << joined[k];
        EXPECT_TRUE(
            fs::exists(fs::path(joined[k]).replace_extension("").string() + "_0" + piece_ext))
            << joined[k];
        EXPECT_EQ(std::string(kind) == "gas" ? gas_differences(whole[k], joined[k])
                                             : parcel_differences(whole[k], joined[k]),
                  "")
            << ranks << " " << joined[k].filename();
      }
    }
  }
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
    // The continued series lists the first run's files (whole or in pieces) and its own; its
    // last output is one rank's, whichever way it was written.
    for (const char* kind : {"gas", "parcels"}) {
      const std::vector<fs::path> listed =
          listed_files(dir / "rest" / (std::string(kind) + ".pvd"));
      ASSERT_EQ(listed.size(), 4u) << kind;  // 0, the stop at step 60, 20 and 40 us
      for (const auto& f : listed) EXPECT_TRUE(fs::exists(f)) << f;
      const fs::path last = listed_files(dir / "one" / (std::string(kind) + ".pvd")).back();
      EXPECT_EQ(std::string(kind) == "gas" ? gas_differences(last, listed.back())
                                           : parcel_differences(last, listed.back()),
                "")
          << first << " then " << then << ": " << listed.back();
    }
  }
  fs::remove_all(dir);
#endif
}

TEST(MpiCli, ACatalystSceneOnTwoRanksRendersWhatOneRankRenders) {
#if !defined(DUSTLIFT_TEST_MPIEXEC) || !defined(DUSTLIFT_TEST_HAS_CATALYST)
  GTEST_SKIP() << "built without MPI or without Catalyst";
#else
  // Rank 0 runs the pipelines on the gathered state. ParaView set up on MPI_COMM_WORLD waited
  // there for the other rank, which waited in the VTK writers: the run hung (hence the
  // timeout, which turns a hang into a failure).
  const auto dir = fresh_dir("mpi_cli_catalyst");
  const std::string scene =
      std::string(DUSTLIFT_SOURCE_DIR) + "/cases/examples/catalyst_by_time.toml";
  auto r = run_command(std::string(DUSTLIFT_BINARY) + " run " + scene + " --threads 1 --out " +
                       (dir / "one").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_command("timeout 300 env " + mpirun2() + " run " + scene + " --threads 1 --out " +
                  (dir / "two").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int renders = 0;
  for (const auto& e : fs::directory_iterator(dir / "one" / "catalyst")) {
    ++renders;
    EXPECT_EQ(read_all(e.path()), read_all(dir / "two" / "catalyst" / e.path().filename()))
        << e.path().filename();
  }
  EXPECT_GE(renders, 6);  // every 10 us over 50 us, and the start
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
