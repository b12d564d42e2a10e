// The surface-height and shock-position observers on a synthetic StateView (no GasSolver):
// rows per output, station columns, no duplicate row when on_finish follows an output.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "insitu/observers.hpp"
#include "insitu/series_table.hpp"
#include "solver/core/field.hpp"
#include "solver/sim/derived_fields.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

struct SyntheticState {
  Grid2D grid{Axis({0.0, 0.01, 0.02, 0.03, 0.04, 0.05}, 2),
              Axis({0.0, 0.001, 0.002, 0.0035, 0.0055, 0.008}, 2)};
  Field2D rho{grid, 1.2}, u{grid}, v{grid}, p{grid, 1e5}, T{grid, 300.0}, alpha_g{grid, 1.0};
  std::filesystem::path dir;
  mutable DerivedFields derived;  // as the run makes them: each view a step of its own
  mutable long long step = 0;

  explicit SyntheticState(const std::string& name)
      : dir(testing::scratch_dir("observers_" + name, false)) {}
  /// Shock at x_s (p = 2e5 behind it); layer alpha_p = 0.5 in the lowest `layer_cells` rows,
  /// the highest of them filled to `top_fill` (alpha_p = 0.5 top_fill).
  void set(double xs, int layer_cells, double top_fill = 1.0) {
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i) {
        p(i, j) = grid.x().center(i) < xs ? 2e5 : 1e5;
        const double alpha_p = j < layer_cells - 1    ? 0.5
                               : j == layer_cells - 1 ? 0.5 * top_fill
                                                      : 0.0;
        alpha_g(i, j) = i < 4 ? 1.0 - alpha_p : 1.0;  // column 4 has no particles
      }
  }
  StateView view(double t) const {
    StateView s;
    s.grid = &grid;
    s.primitives = GasPrimitives{&rho, &u, &v, &p, &T, &alpha_g};
    s.time = t;
    s.output_dir = dir.string();
    s.step = ++step;
    derived.show(s.grid, s.primitives, nullptr, 0.0, s.step);
    s.derived = &derived;
    return s;
  }
};

TEST(SeriesObservers, ShockPositionRowPerOutputWithoutDuplicateAtFinish) {
  SyntheticState s("shock");
  auto observer = make_shock_position_observer({.threshold = 0.05, .p_ambient = 1e5});
  s.set(0.012, 2);
  observer->on_start(s.view(0.0));
  s.set(0.032, 2);
  observer->on_output(s.view(1e-5));
  observer->on_finish(s.view(1e-5));
  const auto t = read_series_h5((s.dir / "series" / "series.h5").string(), "shock_position");
  ASSERT_EQ(t.rows(), 2u);
  // Last high centre 0.015 (then 0.025), level 1.05e5 -> 0.95 of the way to the next centre.
  EXPECT_NEAR(t.column(1)[0], 0.005 + 0.95 * 0.01, 1e-15);
  EXPECT_NEAR(t.column(1)[1], 0.025 + 0.95 * 0.01, 1e-15);
  EXPECT_TRUE(std::filesystem::exists(s.dir / "series" / "shock_position.csv"));
}

TEST(SeriesObservers, SurfaceHeightProfileSkipsEmptyColumnsAndStationsInterpolate) {
  SyntheticState s("surface");
  auto observer = make_surface_height_observer({.threshold = 1e-4, .stations_x = {0.02, 0.045}});
  s.set(0.0, 2);  // alpha_p = 0.5 in rows 0-1: surface at the top face of row 1, 0.002
  observer->on_start(s.view(0.0));
  s.set(0.0, 3, 0.5);  // row 2 (0.002-0.0035) half filled: surface at mid-cell, 0.00275
  observer->on_output(s.view(2e-5));
  observer->on_finish(s.view(2e-5));
  const std::string h5 = (s.dir / "series" / "series.h5").string();
  const auto profile = read_series_h5(h5, "surface_height");
  ASSERT_EQ(profile.rows(), 8u);  // 4 columns with particles x 2 outputs
  EXPECT_NEAR(profile.column(2)[0], 0.002, 1e-15);
  EXPECT_NEAR(profile.column(2)[7], 0.00275, 1e-15);
  EXPECT_EQ(profile.column(1)[3], 0.035);
  const auto stations = read_series_h5(h5, "surface_height_stations");
  ASSERT_EQ(stations.rows(), 2u);
  EXPECT_EQ(stations.header(1), "height_at_x0p02_m");
  EXPECT_NEAR(stations.column(1)[1], 0.00275, 1e-15);
  EXPECT_TRUE(std::isnan(stations.column(2)[1]));  // between a full and an empty column
}

}  // namespace
TEST(SeriesObservers, NearLayerSeriesHoldsTheWindowWithExactLinearVorticity) {
  // u = 3 y + 2 x, v = -5 x on a stretched grid: omega_z = dv/dx - du/dy = -5 - 3 exactly.
  SyntheticState s("near_layer");
  for (int j = 0; j < s.grid.ny(); ++j)
    for (int i = 0; i < s.grid.nx(); ++i) {
      s.u(i, j) = 3.0 * s.grid.y().center(j) + 2.0 * s.grid.x().center(i);
      s.v(i, j) = -5.0 * s.grid.x().center(i);
    }
  s.set(0.0, 2);
  auto observer = make_near_layer_observer({0.01, 0.04, 0.0, 0.004});
  observer->on_output(s.view(2e-5));
  observer->on_finish(s.view(2e-5));  // no duplicate rows
  const auto t = read_series_h5((s.dir / "series" / "series.h5").string(), "near_layer");
  // Centres x = 0.015, 0.025, 0.035 and y = 0.0005, 0.0015, 0.00275 lie in the window.
  ASSERT_EQ(t.rows(), 9u);
  for (std::size_t r = 0; r < t.rows(); ++r) {
    EXPECT_EQ(t.column(0)[r], 2e-5);
    EXPECT_NEAR(t.column(3)[r], 3.0 * t.column(2)[r] + 2.0 * t.column(1)[r], 1e-15);
    EXPECT_NEAR(t.column(5)[r], -8.0, 1e-9);
  }
  EXPECT_EQ(t.columns()[5].unit, "1/s");
  EXPECT_TRUE(std::filesystem::exists(s.dir / "series" / "near_layer.csv"));
  std::filesystem::remove_all(s.dir);
}

}  // namespace dustlift
