// Datasets in pieces (a decomposed run): the .pvtr/.pvtp summaries join the ranks'
// pieces into what one file holds when VTK's parallel XML readers load them; a slab's edge
// columns get the whole grid's vorticity from its ghost columns; a rank's own parcels are
// its table without the ghosts; a continued run removes the summaries and pieces written
// after its checkpoint.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPRectilinearGridReader.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "insitu/gas_cells.hpp"
#include "insitu/parcel_arrays.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/sim/derived_fields.hpp"
#include "support/synthetic_gas.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

namespace fs = std::filesystem;
using testing::synthetic_gas;

fs::path fresh_dir(const std::string& name) {
  return testing::scratch_dir("test_" + name);
}

/// Columns [i0, i1) of `whole` as a piece of their own.
GasCellArrays columns_of(const GasCellArrays& whole, std::size_t i0, std::size_t i1) {
  GasCellArrays p;
  p.x_nodes.assign(whole.x_nodes.begin() + static_cast<long>(i0),
                   whole.x_nodes.begin() + static_cast<long>(i1) + 1);
  p.y_nodes = whole.y_nodes;
  p.resize(i1 - i0, whole.ny());
  for (std::size_t a = 0; a < whole.arrays.size(); ++a)
    for (std::size_t c = 0; c < whole.arrays[a].components.size(); ++c)
      for (std::size_t j = 0; j < whole.ny(); ++j)
        for (std::size_t i = i0; i < i1; ++i)
          p.arrays[a].components[c][(i - i0) + (i1 - i0) * j] =
              whole.arrays[a].components[c][i + whole.nx() * j];
  return p;
}

std::vector<double> values(vtkDataArray* a, int component) {
  std::vector<double> v;
  if (a == nullptr) return v;
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k) v.push_back(a->GetComponent(k, component));
  return v;
}

TEST(GasPieces, TheSummaryJoinsThePiecesIntoTheWholeGrid) {
  const auto dir = fresh_dir("pvtr");
  const GasCellArrays whole = synthetic_gas();
  const std::vector<int> bounds{0, 3, 4, 7};  // a one-column slab in the middle
  std::vector<std::string> sources;
  for (std::size_t r = 0; r + 1 < bounds.size(); ++r) {
    sources.push_back("g_" + std::to_string(r) + ".vtr");
    write_gas_vtr(columns_of(whole, static_cast<std::size_t>(bounds[r]),
                             static_cast<std::size_t>(bounds[r + 1])),
                  (dir / sources.back()).string(), {}, bounds[r]);
  }
  write_gas_pvtr(columns_of(whole, 0, 3), bounds, sources, (dir / "g.pvtr").string());

  vtkNew<vtkXMLPRectilinearGridReader> reader;
  reader->SetFileName((dir / "g.pvtr").string().c_str());
  reader->Update();
  vtkRectilinearGrid* grid = reader->GetOutput();
  ASSERT_EQ(grid->GetNumberOfCells(), 35);
  EXPECT_EQ(values(grid->GetXCoordinates(), 0), whole.x_nodes);
  EXPECT_EQ(values(grid->GetYCoordinates(), 0), whole.y_nodes);
  vtkCellData* cd = grid->GetCellData();
  EXPECT_EQ(cd->GetNumberOfArrays(), 8);
  EXPECT_EQ(values(cd->GetArray("density"), 0), whole.values("density"));
  EXPECT_EQ(values(cd->GetArray("velocity"), 0), whole.values("velocity", 0));
  EXPECT_EQ(values(cd->GetArray("velocity"), 1), whole.values("velocity", 1));
  EXPECT_EQ(values(cd->GetArray("pressure"), 0), whole.values("pressure"));
  EXPECT_EQ(values(cd->GetArray("temperature"), 0), whole.values("temperature"));
  EXPECT_EQ(values(cd->GetArray("mach"), 0), whole.values("mach"));
  EXPECT_EQ(values(cd->GetArray("alpha_p"), 0), whole.values("alpha_p"));
  EXPECT_EQ(values(cd->GetArray("vorticity"), 0), whole.values("vorticity"));
  EXPECT_THROW(write_gas_pvtr(whole, {0, 7}, sources, (dir / "bad.pvtr").string()),
               std::invalid_argument);
}

TEST(GasPieces, ASlabsEdgeColumnsReadItsGhostsForTheWholeGridsVorticity) {
  // u and v that vary nonlinearly along x on a stretched axis: one-sided and centred
  // differences differ at every column.
  const Grid2D whole(Axis({0.0, 0.1, 0.25, 0.45, 0.7, 1.0, 1.4, 1.9}, 2),
                     Axis({0.0, 0.05, 0.12, 0.2}, 2));
  Field2D rho(whole, 1.1), u(whole), v(whole), p(whole, 1e5), T(whole, 290.0), ag(whole, 1.0);
  for (int j = -2; j < whole.ny() + 2; ++j)
    for (int i = -2; i < whole.nx() + 2; ++i) {
      const double x = whole.x().center(i), y = whole.y().center(j);
      u(i, j) = 30.0 + 2.0 * y * y + x;
      v(i, j) = 40.0 + 5.0 * x * x * x + y;
    }
  const auto sound = [](int, int) { return 340.0; };
  DerivedFields whole_fields, slab_fields;  // as the run makes them, one per view
  whole_fields.show(&whole, {&rho, &u, &v, &p, &T, &ag}, nullptr, 0.0, 1);
  GasCellArrays one;
  gather_gas_cells(whole_fields, sound, one);
  const std::vector<int> bounds{0, 3, 7};
  for (int r = 0; r < 2; ++r) {
    const Grid2D slab =
        whole.slice_x(bounds[static_cast<std::size_t>(r)], bounds[static_cast<std::size_t>(r) + 1]);
    // The slab's fields, ghosts included, as its halo leaves them: the whole grid's cells.
    Field2D sr(slab), su(slab), sv(slab), sp(slab), sT(slab), sa(slab);
    for (int j = -2; j < slab.ny() + 2; ++j)
      for (int i = -2; i < slab.nx() + 2; ++i) {
        const int w = i + bounds[static_cast<std::size_t>(r)];
        for (auto [to, from] :
             {std::pair{&sr, &rho}, {&su, &u}, {&sv, &v}, {&sp, &p}, {&sT, &T}, {&sa, &ag}})
          (*to)(i, j) = (*from)(w, j);
      }
    // The slab's axis carries the whole axis's derivative stencils: at a cut they reach into
    // the ghost column, which holds the neighbour's cell.
    GasCellArrays piece;
    slab_fields.show(&slab, {&sr, &su, &sv, &sp, &sT, &sa}, nullptr, 0.0, r + 1);
    gather_gas_cells(slab_fields, sound, piece);
    const GasCellArrays expected =
        columns_of(one, static_cast<std::size_t>(bounds[static_cast<std::size_t>(r)]),
                   static_cast<std::size_t>(bounds[static_cast<std::size_t>(r) + 1]));
    EXPECT_EQ(piece.values("vorticity"), expected.values("vorticity")) << "slab " << r;
    EXPECT_EQ(piece.values("velocity", 0), expected.values("velocity", 0)) << "slab " << r;
    EXPECT_EQ(piece.x_nodes, expected.x_nodes) << "slab " << r;
  }
}

TEST(ParcelPieces, ARanksOwnParcelsAreItsTableWithoutGhostsAndAnEmptyPieceReads) {
  const std::vector<double> x{0.1, 0.2, 0.3, 0.4, 0.5}, y{1.0, 2.0, 3.0, 4.0, 5.0},
      w{7.0, 8.0, 9.0, 10.0, 11.0};
  const std::vector<std::int32_t> id{4, 0, 3, 1, 2};
  ParcelArraysView all;
  all.count = 5;
  all.position = {x, y};
  all.add("velocity", Vec2Columns{w, x});
  all.add("diameter", w);
  all.id = id;
  all.add("charge", y);
  const std::vector<std::uint8_t> ghost{0, 1, 0, 1, 0};
  ParcelArraysCopy store;
  const ParcelArraysView own = kept_rows(all, ghost, store);
  ASSERT_EQ(own.count, 3u);
  EXPECT_EQ(std::vector<double>(own.position.x.begin(), own.position.x.end()),
            (std::vector<double>{0.1, 0.3, 0.5}));
  ASSERT_NE(own.find("velocity"), nullptr);
  EXPECT_EQ(std::vector<double>(own.find("velocity")->y.begin(), own.find("velocity")->y.end()),
            (std::vector<double>{0.1, 0.3, 0.5}));
  EXPECT_EQ(std::vector<std::int32_t>(own.id.begin(), own.id.end()),
            (std::vector<std::int32_t>{4, 3, 2}));
  ASSERT_NE(own.find("charge"), nullptr);
  EXPECT_EQ(own.find("charge")->x[2], 5.0);
  EXPECT_EQ(own.find("temperature"), nullptr);  // absent stays absent
  EXPECT_THROW(kept_rows(all, std::vector<std::uint8_t>{0, 1}, store), std::invalid_argument);

  // Piece 0 holds the own rows, piece 1 no parcel at all (a rank whose parcels all left).
  const auto dir = fresh_dir("pvtp");
  write_parcels_vtp(own, (dir / "p_0.vtp").string());
  ParcelArraysCopy none_store;
  const ParcelArraysView none = kept_rows(all, std::vector<std::uint8_t>(5, 1), none_store);
  EXPECT_EQ(none.count, 0u);
  write_parcels_vtp(none, (dir / "p_1.vtp").string());
  // The empty piece holds every array too (the parallel reader looks each one up in it).
  for (const char* piece : {"p_0.vtp", "p_1.vtp"}) {
    vtkNew<vtkXMLPolyDataReader> one;
    one->SetFileName((dir / piece).string().c_str());
    one->Update();
    EXPECT_EQ(one->GetOutput()->GetPointData()->GetNumberOfArrays(), 4) << piece;
  }
  write_parcels_pvtp(all, {"p_0.vtp", "p_1.vtp"}, (dir / "p.pvtp").string());
  vtkNew<vtkXMLPPolyDataReader> reader;
  reader->SetFileName((dir / "p.pvtp").string().c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  ASSERT_EQ(poly->GetNumberOfPoints(), 3);
  EXPECT_EQ(poly->GetNumberOfVerts(), 3);
  EXPECT_EQ(values(poly->GetPoints()->GetData(), 0), (std::vector<double>{0.1, 0.3, 0.5}));
  EXPECT_EQ(values(poly->GetPointData()->GetArray("id"), 0), (std::vector<double>{4, 3, 2}));
  EXPECT_EQ(values(poly->GetPointData()->GetArray("charge"), 0),
            (std::vector<double>{1.0, 3.0, 5.0}));
  EXPECT_EQ(values(poly->GetPointData()->GetArray("velocity"), 1),
            (std::vector<double>{0.1, 0.3, 0.5}));
}

TEST(VtkSeriesFiles, PiecesAreNumberedWithTheirSummaryAndAResumeRemovesThoseAfterTheCheckpoint) {
  const auto dir = fresh_dir("pieces_resume");
  fs::create_directories(dir / "vtk");
  VtkSeriesFiles rank0(dir.string(), "gas", "pvtr"), rank1(dir.string(), "gas", "pvtr", false);
  for (double t : {0.0, 1e-5}) {
    for (VtkSeriesFiles* f : {&rank0, &rank1}) {
      const std::string summary = f->next_path(t);
      EXPECT_EQ(fs::path(summary).filename().string(),
                (t == 0.0 ? "gas_000000.pvtr.tmp" : "gas_000001.pvtr.tmp"));
      EXPECT_EQ(f->piece_name(1, "vtr"), t == 0.0 ? "gas_000000_1.vtr" : "gas_000001_1.vtr");
      std::ofstream(f->piece_path(f == &rank0 ? 0 : 1, "vtr")) << "piece";
      if (f == &rank0) std::ofstream(summary) << "summary";
      f->commit(t);
    }
  }
  EXPECT_TRUE(fs::exists(dir / "vtk" / "gas_000001.pvtr"));
  EXPECT_EQ(rank0.collection().entries().size(), 2u);
  EXPECT_FALSE(fs::exists(dir / "vtk" / "gas_000001.pvtr.tmp"));
  // A later run (one rank) wrote a whole file and left a temporary; others are not the series'.
  for (const char* name :
       {"gas_000002.vtr", "gas_000002_0.vtr.tmp", "gas_000003.pvtr.tmp", "gas_00000x.vtr",
        "gas_000001_a.vtr", "other_000005.vtr", "gas_000000_0.vtp"})
    std::ofstream(dir / "vtk" / name) << "x";
  // Continue from the checkpoint after the first output: index 1 on.
  Snapshot s;
  VtkSeriesFiles(dir.string(), "gas", "vtr").save_state(s, "g/");
  VtkSeriesFiles::State state = VtkSeriesFiles::read_state(s, "g/");
  state.entries = {{0.0, "vtk/gas_000000.pvtr"}};
  state.next_index = 1;
  VtkSeriesFiles resumed(dir.string(), "gas", "vtr");
  resumed.resume(state, "");
  std::set<std::string> left;
  for (const auto& f : fs::directory_iterator(dir / "vtk"))
    left.insert(f.path().filename().string());
  EXPECT_EQ(left, (std::set<std::string>{"gas_000000.pvtr", "gas_000000_0.vtr", "gas_000000_1.vtr",
                                         "gas_00000x.vtr", "gas_000001_a.vtr", "other_000005.vtr",
                                         "gas_000000_0.vtp"}));
}

}  // namespace
}  // namespace dustlift
