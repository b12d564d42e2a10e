// Parcel observers through adaptor functions (no DEM module): the .vtp series and the
// band-force series with shock arrival found from a moving pressure step.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "insitu/observers.hpp"
#include "insitu/series_table.hpp"
#include "solver/core/field.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) { return testing::scratch_dir("parcel_observers_" + name, false); }

/// 10 x 2 cells of 1 cm; pressure 2e5 behind a step at xs, 1e5 ahead.
struct Gas {
  Grid2D grid{Axis({0.0, 0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1}, 2),
              Axis({0.0, 0.01, 0.02}, 2)};
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
    v.diameter = d;
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
  const std::regex entry("<DataSet timestep=\"[^\"]+\" part=\"0\" file=\"vtk/parcels_00000[01].vtp\"/>");
  EXPECT_EQ(std::distance(std::sregex_iterator(pvd.begin(), pvd.end(), entry), std::sregex_iterator()), 2);
  EXPECT_TRUE(fs::exists(dir / "vtk" / "parcels_000001.vtp"));
  EXPECT_FALSE(fs::exists(dir / "vtk" / "parcels_000002.vtp"));
}

TEST(ParcelObservers, BandForcesAlignedToTheShockArrivalFoundEachStep) {
  const auto dir = fresh_dir("bands");
  Gas gas;
  // Parcel A starts at x0 = 12 mm, B at 32 mm (both in the band), C at 52 mm above it.
  std::vector<double> x0{0.012, 0.032, 0.052}, y0{0.001, 0.001, 0.005}, y{0.001, 0.002, 0.005};
  std::vector<double> drag_x{0.0, 0.0, 0.0}, drag_y{1.0, 5.0, 100.0};
  BandForceOptions options;
  options.bands = {Band{"layer", 0.0, 0.1, 0.0, 0.002}};
  options.averaging.bin_width = 1e-6;
  options.averaging.tau_min = -0.5e-6;  // bins centred on whole microseconds
  options.averaging.tau_max = 20.5e-6;
  options.averaging.contact_window = 1e-5;
  options.shock.p_ambient = 1e5;
  auto observer = make_band_force_observer(options, [&](const StateView&) {
    BandParcelsView v;
    v.count = 3;
    v.initial_position = {x0, y0};
    v.y = y;
    v.force_drag = {drag_x, drag_y};
    return v;
  });
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

}  // namespace
}  // namespace dustlift
