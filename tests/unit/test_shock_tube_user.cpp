// Tried as a shock-tube user would: a pressure gauge as a probe series, gravity
// along a vertical tube (-x), shock tracking when the bed fills the tube, and a parcel as
// large as a cell computed with rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "insitu/outputs.hpp"
#include "insitu/series_table.hpp"
#include "solver/gas/exact_riemann.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/simulation.hpp"
#include "support/run_cli.hpp"

namespace fs = std::filesystem;
using namespace dustlift;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_cli;
using dustlift::testing::write_file;

namespace {

const std::string kSod = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/sod.toml";

/// Runs a scene with its output observers into `dir`.
Simulation& run_with_outputs(Simulation& sim, const fs::path& dir) {
  for (auto& o : make_output_observers(sim.scene(), dir.string())) sim.add_observer(std::move(o));
  sim.run(dir.string());
  return sim;
}

}  // namespace

TEST(ShockTubeUser, AProbeRecordsTheGaugeTraceOfItsCellEveryStep) {
  const auto dir = fresh_dir("probe_every_step");
  Simulation sim(load_scene(
      kSod,
      {"grid.x.cells=200", "output.vtk=false",
       "output.probes=[{ name = \"gauge\", x = 0.8, y = 0.001, fields = [\"p\", \"rho\"] }]"}));
  run_with_outputs(sim, dir);
  const SeriesTable probes = read_series_h5((dir / "series" / "series.h5").string(), "probes");
  ASSERT_EQ(probes.columns().size(), 3u);
  EXPECT_EQ(probes.header(1), "gauge_p_Pa");
  EXPECT_EQ(probes.header(2), "gauge_rho_kg_per_m3");
  EXPECT_EQ(probes.rows(), static_cast<std::size_t>(sim.step()) + 1) << "t = 0 and every step";
  // The last row is the state of the cell holding the probe, bit for bit.
  const int i = sim.grid().x().locate(0.8), j = sim.grid().y().locate(0.001);
  EXPECT_EQ(probes.column(1).back(), (*sim.gas().primitives().p)(i, j));
  EXPECT_EQ(probes.column(2).back(), (*sim.gas().primitives().rho)(i, j));
  EXPECT_EQ(probes.column(1).front(), 0.1);
  // The gauge sees the shock when the exact solution says it arrives (within two cells).
  const ExactRiemannSolver exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  // Shock speed from mass conservation across it (gas at rest ahead).
  const double speed =
      exact.star_density_right() * exact.star_velocity() / (exact.star_density_right() - 0.125);
  const double arrival = (0.8 - 0.5) / speed;
  double seen = NAN;
  for (std::size_t r = 0; r < probes.rows() && std::isnan(seen); ++r)
    if (probes.column(1)[r] > 0.2) seen = probes.column(0)[r];
  EXPECT_NEAR(speed, 1.75216, 1e-5);
  EXPECT_NEAR(seen, arrival, 2.0 * 0.005 / speed) << "exact arrival " << arrival;
  fs::remove_all(dir);
}

TEST(ShockTubeUser, AProbeCadenceSamplesAfterEachMultiple) {
  const auto dir = fresh_dir("probe_cadence");
  Simulation sim(
      load_scene(kSod, {"grid.x.cells=100", "output.vtk=false", "output.probe_interval=0.01",
                        "output.probes=[{ name = \"a\", x = 0.3, y = 0.001 }, { name = \"b\", x = "
                        "0.7, y = 0.004 }]"}));
  run_with_outputs(sim, dir);
  const SeriesTable probes = read_series_h5((dir / "series" / "series.h5").string(), "probes");
  EXPECT_EQ(probes.columns().size(), 1u + 2u * 5u) << "default fields p, rho, u, v, T";
  ASSERT_EQ(probes.rows(), 21u) << "t = 0 and the first step at or after each 0.01 s up to 0.2 s";
  for (std::size_t r = 1; r < probes.rows(); ++r) {
    EXPECT_GE(probes.column(0)[r], 0.01 * static_cast<double>(r) * (1 - 1e-12)) << r;
    EXPECT_LT(probes.column(0)[r], 0.01 * static_cast<double>(r) + 0.002) << r;
  }
  fs::remove_all(dir);
}

TEST(ShockTubeUser, GravityIsAVectorOnTheParcels) {
  // One parcel at rest in still gas, every gas effect off, gravity along -x (a vertical tube
  // along x): symplectic Euler under a constant force gives v = g t.
  const auto dir = fresh_dir("gravity_vector");
  write_file(dir / "one.csv", "x,y,diameter\n0.001,0.001,100e-6\n");
  const std::string scene =
      std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/two_parcel_collision.toml";
  Simulation sim(load_scene(scene, {"particles.layer.file=\"" + (dir / "one.csv").string() + "\"",
                                    "particles.gravity=[-9.81, 0.0]", "run.end_time=1e-4"}));
  ASSERT_EQ(sim.parcels()->size(), 1u);
  sim.run("");
  EXPECT_NEAR(sim.parcels()->vx[0], -9.81 * sim.time(), 1e-12);
  EXPECT_EQ(sim.parcels()->vy[0], 0.0);
  EXPECT_LT(sim.parcels()->x[0], 0.001);
  EXPECT_EQ(sim.parcels()->y[0], 0.001);
  const auto effects = sim.enabled_effects();
  EXPECT_NE(std::find(effects.begin(), effects.end(), "gravity on the parcels: (-9.81, 0) m/s^2"),
            effects.end());
  EXPECT_THROW(load_scene(scene, {"particles.gravity=[1.0]"}), SceneError);
  EXPECT_THROW(load_scene(scene, {"particles.gravity=[-9.81, 0.0]", "particles.g=9.81"}),
               SceneError);
  fs::remove_all(dir);
}

TEST(ShockTubeUser, TheShockIsTrackedWhenTheBedFillsTheTube) {
  // A bed of beads across the whole height of the tube, the shock arriving from the left.
  const auto dir = fresh_dir("bed_fills_tube");
  const std::string quick = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";
  const auto r = run_cli(
      "run " + quick + " --out " + (dir / "o").string() +
      " --threads 1 --set grid.x.start=-0.01 --set grid.x.end=0.01 --set grid.x.cells_below=4"
      " --set grid.y.end=0.002 --set grid.y.uniform_end=0.002 --set grid.y.cells_above=0"
      " --set particles.layer.y_max=0.002 --set particles.layer.volume_fraction=0.3"
      " --set particles.layer.x_max=0.01 --set run.end_time=1.5e-5 --set output.interval=5e-6"
      " --set output.vtk=false");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const SeriesTable shock =
      read_series_h5((dir / "o" / "series" / "series.h5").string(), "shock_position");
  ASSERT_EQ(shock.rows(), 4u);
  for (std::size_t k = 0; k < shock.rows(); ++k)
    EXPECT_TRUE(std::isfinite(shock.column(1)[k])) << "row " << k;
  EXPECT_GT(shock.column(1).back(), shock.column(1).front()) << "it moves on";
  fs::remove_all(dir);
}

TEST(ShockTubeUser, AParcelAsLargeAsACellFitsDespiteRounding) {
  // 2.0 m / 1000 cells computes as a hair less than 0.002 m.
  const std::string grid =
      " --set \"grid.x={ start = 0.0, end = 2.0, cells = 1000 }\" --set \"grid.y={ start = 0.0, "
      "end = 0.02, cells = 10 }\""
      " --set particles.layer.x_max=2.0 --set particles.layer.y_min=0.0 --set "
      "particles.layer.y_max=0.01"
      " --set particles.layer.volume_fraction=0.3";
  const std::string scene =
      std::string(DUSTLIFT_SOURCE_DIR) +
      "/cases/quickstart.toml --set initial.position=0.5 --set run.end_time=1e-6";
  auto r = run_cli("info " + scene + grid + " --set particles.diameter=0.002");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("info " + scene + grid + " --set particles.diameter=0.0020001");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(
      r.output.find("parcels of 0.0020001 m are larger than the smallest grid cell (0.002 m)"),
      std::string::npos)
      << r.output;
}
