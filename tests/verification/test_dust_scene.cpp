// The shock-over-dust scene end to end (reduced quickstart): the coupled run stays physical
// (finite, rho and p > 0, 0 < alpha_g <= 1), the shock travels at its Rankine-Hugoniot speed
// above the layer, the layer is pushed down behind the shock, and the CLI writes every output
// a user plots (VTK collections, series, series.h5).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "solver/dem/parcel_system.hpp"
#include "solver/sim/simulation.hpp"
#include "support/run_cli.hpp"

using namespace dustlift;
namespace fs = std::filesystem;

namespace {

const std::string kQuickstart = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";

/// The quickstart scene on a 30 mm jittered layer (about 4,500 parcels with free play between
/// them, which the shock's flow presses down).
Scene reduced_scene() {
  return load_scene(kQuickstart, {"grid.x.start=-0.02", "grid.x.end=0.03", "grid.x.cells_below=10",
                                  "particles.layer.x_max=0.03", "grid.y.end=0.02", "grid.y.cells_above=8",
                                  "particles.layer.arrangement=\"jittered_lattice\""});
}

}  // namespace

TEST(DustScene, CoupledShockOverLayerStaysPhysical) {
  const Scene scene = reduced_scene();
  Simulation sim(scene);
  ASSERT_NE(sim.parcels(), nullptr);
  const ParcelSystem& ps = *sim.parcels();
  EXPECT_NEAR(static_cast<double>(ps.size()), 0.59 * 0.03 * 0.002 / (M_PI / 4 * 1e-8), 30.0);
  double mean_y0 = 0.0;
  for (std::size_t k = 0; k < ps.size(); ++k) mean_y0 += ps.y[k] / static_cast<double>(ps.size());
  while (sim.time() < 40e-6) sim.advance(40e-6 - sim.time());

  const GasPrimitives g = sim.gas().primitives();
  const Grid2D& grid = sim.grid();
  for (int j = 0; j < grid.ny(); ++j) {
    for (int i = 0; i < grid.nx(); ++i) {
      ASSERT_TRUE(std::isfinite((*g.rho)(i, j)) && (*g.rho)(i, j) > 0.0) << i << "," << j;
      ASSERT_TRUE(std::isfinite((*g.p)(i, j)) && (*g.p)(i, j) > 0.0) << i << "," << j;
      ASSERT_GT((*g.alpha_g)(i, j), 0.0);
      ASSERT_LE((*g.alpha_g)(i, j), 1.0);
    }
  }
  double mean_y = 0.0, mean_vx = 0.0;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    ASSERT_TRUE(std::isfinite(ps.x[k]) && std::isfinite(ps.y[k]));
    mean_y += ps.y[k] / static_cast<double>(ps.size());
    mean_vx += ps.vx[k] / static_cast<double>(ps.size());
  }
  // The shock-induced flow drags the layer downstream and presses it down (paper Fig. 10a, c).
  EXPECT_GT(mean_vx, 0.1);
  EXPECT_LT(mean_y, mean_y0);
  // Above the layer the shock runs at W = M_s c_1 = 500.7 m/s: from x = -5 mm to about 15 mm.
  int shock_i = -1;
  const int j_above = grid.y().locate(0.01);
  for (int i = 0; i < grid.nx(); ++i)
    if ((*g.p)(i, j_above) > 1.05 * 101e3) shock_i = i;
  ASSERT_GE(shock_i, 0);
  EXPECT_NEAR(grid.x().center(shock_i), -0.005 + 500.7 * 40e-6, 2e-3);
}

TEST(DustScene, CliWritesEveryOutputOfADustRun) {
  const auto dir = dustlift::testing::fresh_dir("dust_cli");
  const auto r = dustlift::testing::run_cli(
      "run " + kQuickstart + " --out " + dir.string() +
      " --set grid.x.start=-0.02 --set grid.x.end=0.03 --set grid.x.cells_below=10 --set particles.layer.x_max=0.03"
      " --set grid.y.end=0.02 --set grid.y.cells_above=8 --set run.end_time=2e-5 --set output.interval=1e-5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"gas.pvd", "parcels.pvd", "scene.resolved.toml", "run.log", "series/series.h5",
                        "series/shock_position.csv", "series/surface_height.csv", "series/surface_height_stations.csv",
                        "series/forces_surface.csv", "series/forces_middle.csv", "series/near_layer.csv",
                        "vtk/gas_000002.vtr", "vtk/parcels_000002.vtp"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  EXPECT_NE(r.output.find("DEM parcels"), std::string::npos) << r.output;
  fs::remove_all(dir);
}
