// The .vtr/.vtp writers: files load with VTK's XML readers, hold every named array with
// the right tuple and component counts, values round-trip; the .pvd lists files and times.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLRectilinearGridReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/vtk_datasets.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/sim/derived_fields.hpp"
#include "solver/sim/gas_fields.hpp"
#include "support/synthetic_gas.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

using testing::synthetic_gas;

std::filesystem::path fresh_dir(const std::string& name) {
  return testing::scratch_dir("test_" + name);
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void expect_array(vtkDataArray* array, const std::vector<double>& expected, const char* name) {
  ASSERT_NE(array, nullptr) << "missing array " << name;
  ASSERT_EQ(array->GetNumberOfComponents(), 1) << name;
  ASSERT_EQ(array->GetNumberOfTuples(), static_cast<vtkIdType>(expected.size())) << name;
  for (std::size_t k = 0; k < expected.size(); ++k)
    EXPECT_EQ(array->GetComponent(static_cast<vtkIdType>(k), 0), expected[k]) << name << " " << k;
}

void expect_vector(vtkDataArray* array, const std::vector<double>& x, const std::vector<double>& y,
                   const char* name) {
  ASSERT_NE(array, nullptr) << "missing array " << name;
  ASSERT_EQ(array->GetNumberOfComponents(), 3) << name;
  ASSERT_EQ(array->GetNumberOfTuples(), static_cast<vtkIdType>(x.size())) << name;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const auto id = static_cast<vtkIdType>(k);
    EXPECT_EQ(array->GetComponent(id, 0), x[k]) << name << " " << k;
    EXPECT_EQ(array->GetComponent(id, 1), y[k]) << name << " " << k;
    EXPECT_EQ(array->GetComponent(id, 2), 0.0) << name << " " << k;
  }
}

TEST(VtkGasWriter, RectilinearGridRoundTripsEveryArray) {
  const auto dir = fresh_dir("vtr");
  const GasCellArrays gas = synthetic_gas();
  const auto path = (dir / "gas.vtr").string();
  write_gas_vtr(gas, path);
  // Inline binary + zlib, not appended (ParaView 5.11 reads appended data as empty).
  const std::string text = read_text(path);
  EXPECT_NE(text.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  EXPECT_NE(text.find("format=\"binary\""), std::string::npos);
  EXPECT_EQ(text.find("AppendedData"), std::string::npos);

  vtkNew<vtkXMLRectilinearGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkRectilinearGrid* grid = reader->GetOutput();
  ASSERT_EQ(grid->GetNumberOfCells(), 35);
  ASSERT_EQ(grid->GetNumberOfPoints(), 8 * 6);
  int dims[3];
  grid->GetDimensions(dims);
  EXPECT_EQ(dims[0], 8);
  EXPECT_EQ(dims[1], 6);
  EXPECT_EQ(dims[2], 1);
  expect_array(grid->GetXCoordinates(), gas.x_nodes, "x nodes");
  expect_array(grid->GetYCoordinates(), gas.y_nodes, "y nodes");
  vtkCellData* cd = grid->GetCellData();
  EXPECT_EQ(cd->GetNumberOfArrays(), 8);
  expect_array(cd->GetArray("density"), gas.values("density"), "density");
  expect_vector(cd->GetArray("velocity"), gas.values("velocity", 0), gas.values("velocity", 1),
                "velocity");
  expect_array(cd->GetArray("pressure"), gas.values("pressure"), "pressure");
  expect_array(cd->GetArray("temperature"), gas.values("temperature"), "temperature");
  expect_array(cd->GetArray("mach"), gas.values("mach"), "mach");
  expect_array(cd->GetArray("alpha_p"), gas.values("alpha_p"), "alpha_p");
  expect_array(cd->GetArray("vorticity"), gas.values("vorticity"), "vorticity");
  expect_array(cd->GetArray("dust_concentration"), gas.values("dust_concentration"),
               "dust_concentration");
  // Cell (i, j) = (3, 2) is VTK cell 3 + 7*2 and lies between the matching nodes.
  double bounds[6];
  grid->GetCell(3 + 7 * 2)->GetBounds(bounds);
  EXPECT_EQ(bounds[0], gas.x_nodes[3]);
  EXPECT_EQ(bounds[1], gas.x_nodes[4]);
  EXPECT_EQ(bounds[2], gas.y_nodes[2]);
  EXPECT_EQ(bounds[3], gas.y_nodes[3]);
}

TEST(VtkGasWriter, MismatchedArrayIsRejected) {
  GasCellArrays gas = synthetic_gas();
  gas.values("pressure").pop_back();
  EXPECT_THROW(write_gas_vtr(gas, (fresh_dir("bad") / "x.vtr").string()), std::invalid_argument);
}

TEST(GasCells, GatheredFromFieldsWithMachAlphaPAndVorticity) {
  const Grid2D grid(Axis({0.0, 0.1, 0.25, 0.45, 0.7}, 2), Axis({0.0, 0.05, 0.12, 0.2}, 2));
  Field2D rho(grid, 1.1), u(grid), v(grid), p(grid, 1e5), T(grid, 290.0), ag(grid, 1.0);
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      u(i, j) = 30.0 + 2.0 * grid.y().center(j);  // du/dy = 2
      v(i, j) = 40.0 + 5.0 * grid.x().center(i);  // dv/dx = 5
      ag(i, j) = 1.0 - 0.01 * (i + 10 * j);
    }
  u(-1, 0) = 1e9;  // ghosts must not leak into the output
  const GasPrimitives prims{&rho, &u, &v, &p, &T, &ag};
  // The deposited alpha_p (here 1 - alpha_g) and 1500 kg/m^3 particles: c = 1500 alpha_p.
  Field2D ap(grid);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) ap(i, j) = 0.01 * (i + 10 * j);
  DerivedFields fields;
  fields.show(&grid, prims, &ap, 1500.0, 1);
  GasCellArrays out;
  gather_gas_cells(
      fields, [](int i, int j) { return 340.0 + i + 2.0 * j; }, out);
  ASSERT_EQ(out.nx(), 4u);
  ASSERT_EQ(out.ny(), 3u);
  EXPECT_EQ(out.x_nodes, grid.x().interior_faces());
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      const std::size_t k = static_cast<std::size_t>(i + 4 * j);
      EXPECT_NEAR(out.values("mach")[k], std::hypot(u(i, j), v(i, j)) / (340.0 + i + 2.0 * j),
                  1e-15);
      EXPECT_NEAR(out.values("alpha_p")[k], 0.01 * (i + 10 * j), 1e-15);
      EXPECT_NEAR(out.values("vorticity")[k], 5.0 - 2.0, 1e-11);
      EXPECT_EQ(out.values("dust_concentration")[k], 1500.0 * ap(i, j));
      EXPECT_EQ(out.values("velocity", 0)[k], u(i, j));
    }
}

TEST(GasCells, OneArrayPerRegistryFieldInItsOrder) {
  // The writers and Catalyst hold the registry's fields, in its order, under its names.
  const GasCellArrays gas = synthetic_gas();
  ASSERT_EQ(gas.arrays.size(), gas_fields().size());
  ASSERT_EQ(gas_fields().size(), 8u);
  for (std::size_t k = 0; k < gas.arrays.size(); ++k) {
    EXPECT_EQ(gas.arrays[k].name, gas_fields()[k].name);
    EXPECT_EQ(gas.arrays[k].components.size(),
              static_cast<std::size_t>(gas_fields()[k].components));
  }
  vtkSmartPointer<vtkRectilinearGrid> grid = make_gas_grid(gas);
  set_gas_cell_data(grid, gas);
  for (std::size_t k = 0; k < gas.arrays.size(); ++k)
    EXPECT_EQ(grid->GetCellData()->GetArrayName(static_cast<int>(k)), gas.arrays[k].name);
  EXPECT_EQ(gas_fields()[gas_field_index("dust_concentration")].unit, "kg/m^3");
  EXPECT_EQ(gas_fields()[gas_field_index("vorticity")].made, GasFieldMade::OncePerStep);
  EXPECT_THROW(gas_field_index("no_such_field"), std::invalid_argument);
}

TEST(VtkParcelWriter, PolyDataRoundTripsEveryArray) {
  const std::size_t n = 11;
  std::vector<std::vector<double>> a(22, std::vector<double>(n));
  for (std::size_t c = 0; c < a.size(); ++c)
    for (std::size_t k = 0; k < n; ++k) a[c][k] = 1e-3 * static_cast<double>(c * 100 + k) + 0.5;
  ParcelArraysView view;
  view.count = n;
  view.position = {a[0], a[1]};
  view.add("velocity", Vec2Columns{a[2], a[3]});
  view.add("angular_velocity", a[4]);
  view.add("temperature", a[5]);
  view.add("diameter", a[6]);
  view.add("initial_position", Vec2Columns{a[7], a[8]});
  view.add("force_contact", Vec2Columns{a[9], a[10]});
  view.add("force_drag", Vec2Columns{a[11], a[12]});
  view.add("force_magnus", Vec2Columns{a[13], a[14]});
  view.add("force_pressure", Vec2Columns{a[15], a[16]});
  const auto path = (fresh_dir("vtp") / "p.vtp").string();
  write_parcels_vtp(view, path);

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  ASSERT_EQ(poly->GetNumberOfPoints(), static_cast<vtkIdType>(n));
  ASSERT_EQ(poly->GetNumberOfVerts(), static_cast<vtkIdType>(n));
  ASSERT_EQ(poly->GetNumberOfCells(), static_cast<vtkIdType>(n));
  for (std::size_t k = 0; k < n; ++k) {
    double xyz[3];
    poly->GetPoint(static_cast<vtkIdType>(k), xyz);
    EXPECT_EQ(xyz[0], a[0][k]);
    EXPECT_EQ(xyz[1], a[1][k]);
    EXPECT_EQ(xyz[2], 0.0);
  }
  vtkPointData* pd = poly->GetPointData();
  EXPECT_EQ(pd->GetNumberOfArrays(), 9);
  expect_vector(pd->GetArray("velocity"), a[2], a[3], "velocity");
  expect_array(pd->GetArray("angular_velocity"), a[4], "angular_velocity");
  expect_array(pd->GetArray("temperature"), a[5], "temperature");
  expect_array(pd->GetArray("diameter"), a[6], "diameter");
  expect_vector(pd->GetArray("initial_position"), a[7], a[8], "initial_position");
  expect_vector(pd->GetArray("force_contact"), a[9], a[10], "force_contact");
  expect_vector(pd->GetArray("force_drag"), a[11], a[12], "force_drag");
  expect_vector(pd->GetArray("force_magnus"), a[13], a[14], "force_magnus");
  expect_vector(pd->GetArray("force_pressure"), a[15], a[16], "force_pressure");
}

TEST(VtkParcelWriter, IdExtraColumnsAndFieldDataSayWhatTheFileIs) {
  // Points in a sorted (not id) order: the id array names each parcel for ParaView.
  std::vector<double> x{0.3, 0.1, 0.2}, y{0.0, 0.01, 0.02}, extra{7.0, 8.0, 9.0};
  const std::vector<std::int32_t> id{2, 0, 1};
  ParcelArraysView view;
  view.count = 3;
  view.position = {x, y};
  view.id = id;
  view.add("gas_rotation", extra);
  const auto path = (fresh_dir("vtp_id") / "p.vtp").string();
  write_parcels_vtp(view, path, VtkFileInfo{2.5e-5, "0.1.0 (git test)", "dustlift run s.toml"});
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  vtkDataArray* ids = poly->GetPointData()->GetArray("id");
  ASSERT_NE(ids, nullptr);
  EXPECT_EQ(ids->GetDataType(), VTK_INT);
  for (vtkIdType k = 0; k < 3; ++k)
    EXPECT_EQ(ids->GetComponent(k, 0), id[static_cast<std::size_t>(k)]);
  expect_array(poly->GetPointData()->GetArray("gas_rotation"), extra, "gas_rotation");
  vtkFieldData* fd = poly->GetFieldData();
  ASSERT_NE(fd->GetArray("TimeValue"), nullptr);
  EXPECT_EQ(fd->GetArray("TimeValue")->GetComponent(0, 0), 2.5e-5);
  auto* version = vtkStringArray::SafeDownCast(fd->GetAbstractArray("code_version"));
  auto* command = vtkStringArray::SafeDownCast(fd->GetAbstractArray("command_line"));
  ASSERT_NE(version, nullptr);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(version->GetValue(0), "0.1.0 (git test)");
  EXPECT_EQ(command->GetValue(0), "dustlift run s.toml");
  view.arrays.front().x = std::span<const double>(extra).first(2);
  EXPECT_THROW(write_parcels_vtp(view, path), std::invalid_argument);
}

TEST(VtkParcelWriter, OptionalArraysAreOmittedAndWrongLengthsRejected) {
  std::vector<double> x{0.1, 0.2, 0.3}, y{0.0, 0.01, 0.02}, d{1e-4, 1e-4, 1e-4};
  ParcelArraysView view;
  view.count = 3;
  view.position = {x, y};
  view.add("diameter", d);
  const auto path = (fresh_dir("vtp_min") / "p.vtp").string();
  write_parcels_vtp(view, path);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 3);
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetNumberOfArrays(), 1);
  std::vector<double> short_t{300.0};
  view.add("temperature", short_t);
  EXPECT_THROW(write_parcels_vtp(view, path), std::invalid_argument);
}

TEST(PvdCollection, ListsEveryFileWithItsTimeAndReplacesARepeatedTime) {
  const auto dir = fresh_dir("pvd");
  std::vector<double> x{0.1, 0.2}, y{0.0, 0.01};
  ParcelArraysView view;
  view.count = 2;
  view.position = {x, y};
  ParcelSeriesWriter writer(dir.string());
  writer.write(view, 0.0);
  writer.write(view, 2.5e-5);
  writer.write(view, 5.0e-5);
  writer.write(view, 5.0e-5);  // on_finish right after the last output: same file again
  const std::string text = read_text(dir / "parcels.pvd");
  const std::regex entry("<DataSet timestep=\"([^\"]+)\" part=\"0\" file=\"([^\"]+)\"/>");
  std::vector<std::pair<double, std::string>> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry);
       it != std::sregex_iterator(); ++it)
    found.emplace_back(std::stod((*it)[1]), (*it)[2]);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0], std::make_pair(0.0, std::string("vtk/parcels_000000.vtp")));
  EXPECT_EQ(found[1], std::make_pair(2.5e-5, std::string("vtk/parcels_000001.vtp")));
  EXPECT_EQ(found[2], std::make_pair(5.0e-5, std::string("vtk/parcels_000002.vtp")));
  for (const auto& f : found) EXPECT_TRUE(std::filesystem::exists(dir / f.second)) << f.second;
  EXPECT_FALSE(std::filesystem::exists(dir / "vtk/parcels_000003.vtp"));
  EXPECT_FALSE(std::filesystem::exists(dir / "parcels.pvd.tmp"));
  EXPECT_NE(text.find("type=\"Collection\""), std::string::npos);
}

}  // namespace
}  // namespace dustlift

namespace dustlift {
namespace {

TEST(VtkGasWriterObserver, WritesOneFilePerOutputTimeAndAValidCollection) {
  const auto dir = fresh_dir("observer");
  const Grid2D grid(Axis({0.0, 0.1, 0.25, 0.45}, 2), Axis({0.0, 0.05, 0.12}, 2));
  Field2D rho(grid, 1.2), u(grid, 30.0), v(grid, 40.0), p(grid, 1e5), T(grid, 290.0),
      ag(grid, 0.75);
  StateView view;
  view.grid = &grid;
  view.primitives = GasPrimitives{&rho, &u, &v, &p, &T, &ag};
  view.output_dir = dir.string();
  DerivedFields fields;  // as the run makes them, a step per view
  fields.show(view.grid, view.primitives, nullptr, 0.0, 0);
  view.derived = &fields;
  // Ideal-gas sound speed from the view's fields (no GasSolver in this test).
  auto writer = make_vtk_gas_writer([](const StateView& s, int i, int j) {
    return std::sqrt(1.4 * (*s.primitives.p)(i, j) / (*s.primitives.rho)(i, j));
  });
  writer->on_start(view);
  view.time = 1e-5;
  view.step = 1;
  p.fill(2e5);
  fields.show(view.grid, view.primitives, nullptr, 0.0, view.step);
  writer->on_output(view);
  writer->on_finish(view);  // same time: overwrites gas_000001.vtr
  const std::string pvd = read_text(dir / "gas.pvd");
  EXPECT_NE(pvd.find("timestep=\"0\" part=\"0\" file=\"vtk/gas_000000.vtr\""), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"1e-05\" part=\"0\" file=\"vtk/gas_000001.vtr\""),
            std::string::npos)
      << pvd;
  EXPECT_FALSE(std::filesystem::exists(dir / "vtk" / "gas_000002.vtr"));
  vtkNew<vtkXMLRectilinearGridReader> reader;
  reader->SetFileName((dir / "vtk" / "gas_000001.vtr").string().c_str());
  reader->Update();
  vtkCellData* cd = reader->GetOutput()->GetCellData();
  ASSERT_EQ(reader->GetOutput()->GetNumberOfCells(), 6);
  EXPECT_NEAR(cd->GetArray("mach")->GetComponent(4, 0), 50.0 / std::sqrt(1.4 * 2e5 / 1.2), 1e-14);
  EXPECT_NEAR(cd->GetArray("alpha_p")->GetComponent(4, 0), 0.25, 1e-15);
  EXPECT_EQ(cd->GetArray("pressure")->GetComponent(5, 0), 2e5);
}

}  // namespace
}  // namespace dustlift
