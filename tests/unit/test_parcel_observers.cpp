// Parcel observers through adaptor functions (no DEM module): the .vtp series and the
// band-force series with shock arrival found from a moving pressure step.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>

#include "insitu/observers.hpp"
#include "insitu/series_table.hpp"
#include "solver/core/field.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  return testing::scratch_dir("parcel_observers_" + name, false);
}

/// Faces of `cells` cells of 1 cm from x = 0.
std::vector<double> centimetre_faces(int cells) {
  std::vector<double> faces;
  for (int i = 0; i <= cells; ++i) faces.push_back(0.01 * i);
  return faces;
}

/// cells x 2 cells of 1 cm (10 by default); pressure 2e5 behind a step at xs, 1e5 ahead.
struct Gas {
  explicit Gas(int cells = 10)
      : grid(Axis(centimetre_faces(cells), 2), Axis({0.0, 0.01, 0.02}, 2)) {}
  Grid2D grid;
  Field2D rho{grid, 1.2}, u{grid}, v{grid}, p{grid, 1e5}, T{grid, 300.0}, alpha_g{grid, 1.0};
  void step_at(double xs) {
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i) p(i, j) = grid.x().center(i) < xs ? 2e5 : 1e5;
  }
  StateView view(double t, const fs::path& dir) const {
    StateView s;
    s.grid = &grid;
    s.primitives = GasPrimitives{&rho, &u, &v, &p, &T, &alpha_g};
    s.time = t;
    s.output_dir = dir.string();
    return s;
  }
};

TEST(ParcelObservers, VtkParcelWriterWritesOneFilePerOutputThroughTheAdaptor) {
  const auto dir = fresh_dir("vtp");
  Gas gas;
  std::vector<double> x{0.01, 0.02, 0.03}, y{0.001, 0.002, 0.003}, d{1e-4, 1e-4, 1e-4};
  auto writer = make_vtk_parcel_writer([&](const StateView&) {
    ParcelArraysView v;
    v.count = x.size();
    v.position = {x, y};
    v.add("diameter", d);
    return v;
  });
  writer->on_start(gas.view(0.0, dir));
  y[1] = 0.004;
  writer->on_output(gas.view(1e-5, dir));
  writer->on_finish(gas.view(1e-5, dir));
  std::ifstream in(dir / "parcels.pvd");
  std::stringstream text;
  text << in.rdbuf();
  const std::string pvd = text.str();
  const std::regex entry(
      "<DataSet timestep=\"[^\"]+\" part=\"0\" file=\"vtk/parcels_00000[01].vtp\"/>");
  EXPECT_EQ(
      std::distance(std::sregex_iterator(pvd.begin(), pvd.end(), entry), std::sregex_iterator()),
      2);
  EXPECT_TRUE(fs::exists(dir / "vtk" / "parcels_000001.vtp"));
  EXPECT_FALSE(fs::exists(dir / "vtk" / "parcels_000002.vtp"));
}

/// Three parcels with fixed drag forces, seen by a band-force observer whose band holds
/// initial positions 0 <= x0 < band_x_max, 0 <= y0 < 2 mm; 1 us bins centred on whole
/// microseconds.
struct BandParcels {
  std::vector<double> x0, y0, y, drag_x{0.0, 0.0, 0.0}, drag_y{1.0, 5.0, 100.0};
  std::unique_ptr<Observer> observer(double band_x_max) {
    BandForceOptions options;
    options.bands = {Band{"layer", 0.0, band_x_max, 0.0, 0.002}};
    options.averaging.bin_width = 1e-6;
    options.averaging.tau_min = -0.5e-6;
    options.averaging.tau_max = 20.5e-6;
    options.averaging.contact_window = 1e-5;
    options.shock.p_ambient = 1e5;
    return make_band_force_observer(options, [this](const StateView&) {
      BandParcelsView v;
      v.count = 3;
      v.initial_position = {x0, y0};
      v.y = y;
      v.force_drag = {drag_x, drag_y};
      return v;
    });
  }
};

TEST(ParcelObservers, BandForcesAlignedToTheShockArrivalFoundEachStep) {
  const auto dir = fresh_dir("bands");
  Gas gas;
  // Parcel A starts at x0 = 12 mm, B at 32 mm (both in the band), C at 52 mm above it.
  BandParcels parcels{{0.012, 0.032, 0.052}, {0.001, 0.001, 0.005}, {0.001, 0.002, 0.005}};
  auto observer = parcels.observer(0.1);
  // Step m at t = m us, shock at xs = 10 mm * m + 1 mm: the filter reports
  // 10 mm * m + 4.5 mm, so A arrives at m = 1 and B at m = 3.
  for (int m = 0; m < 10; ++m) {
    gas.step_at(0.01 * m + 0.001);
    const StateView view = gas.view(m * 1e-6, dir);
    if (m == 0) observer->on_start(view);
    observer->on_step(view);
    if (m == 5) observer->on_output(view);
  }
  observer->on_finish(gas.view(9e-6, dir));
  const auto table = read_series_h5((dir / "series" / "series.h5").string(), "forces_layer");
  // A: tau = 0..8 us, B: tau = 0..6 us -> bins 0-6 hold both (mean 3), bins 7-8 only A.
  ASSERT_EQ(table.rows(), 9u);
  for (std::size_t r = 0; r < 9; ++r) {
    SCOPED_TRACE("row " + std::to_string(r));
    EXPECT_NEAR(table.column(0)[r], r * 1e-6, 1e-18);
    EXPECT_EQ(table.column(1)[r], r <= 6 ? 2.0 : 1.0);
    EXPECT_EQ(table.column(6)[r], r <= 6 ? 3.0 : 1.0);  // drag_y
  }
  EXPECT_TRUE(fs::exists(dir / "series" / "forces_layer.csv"));
}

TEST(ParcelObservers, PressurePulseFarAheadOfTheShockDoesNotDateTheArrivalsEarly) {
  // As above on 40 cells, with a 1.5 p0 pulse in the cell at 205 mm at steps 2 and 6: the
  // shock cannot move 8 cells in a step, so the pulse is not a shock position. Counted
  // from it, A (12 mm) and B (32 mm) would both have arrived at step 2 and C (182 mm) too.
  const auto dir = fresh_dir("bands_pulse");
  Gas gas(40);
  BandParcels parcels{{0.012, 0.032, 0.182}, {0.001, 0.001, 0.001}, {0.001, 0.002, 0.001}};
  auto observer = parcels.observer(0.4);
  for (int m = 0; m < 10; ++m) {
    gas.step_at(0.01 * m + 0.001);
    if (m == 2 || m == 6) {
      for (int j = 0; j < gas.grid.ny(); ++j) gas.p(20, j) = 1.5e5;
    }
    const StateView view = gas.view(m * 1e-6, dir);
    if (m == 0) observer->on_start(view);
    observer->on_step(view);
  }
  ::testing::internal::CaptureStderr();
  observer->on_finish(gas.view(9e-6, dir));
  const std::string warning = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(
      warning.find(
          "band filter: 2 shock positions ignored, each more than 8 cells beyond the farthest"),
      std::string::npos)
      << warning;
  const auto table = read_series_h5((dir / "series" / "series.h5").string(), "forces_layer");
  // The same bins as without the pulse: A from step 1, B from step 3, C never.
  ASSERT_EQ(table.rows(), 9u);
  for (std::size_t r = 0; r < 9; ++r) {
    SCOPED_TRACE("row " + std::to_string(r));
    EXPECT_EQ(table.column(1)[r], r <= 6 ? 2.0 : 1.0);
    EXPECT_EQ(table.column(6)[r], r <= 6 ? 3.0 : 1.0);  // drag_y
  }
}

}  // namespace
}  // namespace dustlift
