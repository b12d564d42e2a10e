// The shock-particle-curtain validation case (cases/validation/curtain_ms166.toml, docs/
// validation.md) on a reduced channel: the curtain's fronts 240 us after the shock against the
// measured ones (Wagner et al. 2012, as plotted by Ling et al. 2012, Fig. 14), and what the
// added-mass force contributes. The full case's remaining gap (the curtain spreads ~20 % less
// than measured in the first 250 us, as in Ling et al.'s own simulation) is why the bound is
// two error bars, not one; a drag or force that regressed moves the fronts by more.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "insitu/parcel_fronts.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"

using namespace dustlift;

namespace {

const std::string kCase = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/validation/curtain_ms166.toml";
const std::string kData =
    std::string(DUSTLIFT_SOURCE_DIR) + "/cases/validation/data/curtain_ms166_fronts_experiment.csv";

struct Measured {
  double t_us, x_mm, minus_mm, plus_mm;
};

/// The measured point of `front` ("upstream", "downstream") nearest to t_us.
Measured measured(const std::string& front, double t_us) {
  std::ifstream in(kData);
  std::string line;
  Measured best{-1.0, 0.0, 0.0, 0.0};
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) f.push_back(c);
    f.resize(6);
    if (f[0] != front) continue;
    const double t = std::stod(f[1]), x = std::stod(f[2]);
    const Measured m = f[3].empty() ? Measured{t, x, std::stod(f[5]), std::stod(f[5])}
                                    : Measured{t, x, x - std::stod(f[3]), std::stod(f[4]) - x};
    if (best.t_us < 0.0 || std::abs(t - t_us) < std::abs(best.t_us - t_us)) best = m;
  }
  return best;
}

/// The fronts (mm from the curtain's upstream edge, x = 0) at t (s) on a 4 mm channel.
ParcelFronts fronts_at(double t, bool added_mass) {
  const Scene scene =
      load_scene(kCase, {"grid.y.end=0.004", "grid.y.cells=16", "particles.layer.y_max=0.004",
                         std::string("coupling.added_mass=") + (added_mass ? "true" : "false")});
  Simulation sim(scene);
  while (sim.time() < t) sim.advance(t - sim.time());
  const ParcelSystem& p = *sim.parcels();
  std::vector<std::size_t> order;
  ParcelFronts f = parcel_fronts(p.x, p.n_real, 0.01, order);
  for (double* x : {&f.x_min, &f.x_max, &f.x_low, &f.x_high}) *x *= 1e3;
  return f;
}

/// |ours - measured| in units of the error bar on that side.
double bars(double ours, const Measured& m) {
  const double d = ours - m.x_mm;
  return std::abs(d) / (d >= 0.0 ? m.plus_mm : m.minus_mm);
}

}  // namespace

TEST(Curtain, FrontsAfter240usAgainstTheExperiment) {
  const Measured up = measured("upstream", 240.0), down = measured("downstream", 240.0);
  ASSERT_NEAR(up.t_us, 240.8, 0.5);
  ASSERT_NEAR(down.t_us, 240.8, 0.5);
  const ParcelFronts with = fronts_at(down.t_us * 1e-6, true);
  const ParcelFronts without = fronts_at(down.t_us * 1e-6, false);
  std::printf(
      "t = %.1f us: upstream %.2f mm (measured %.2f), downstream %.2f mm (measured %.2f); "
      "without added mass %.2f / %.2f mm\n",
      down.t_us, with.x_min, up.x_mm, with.x_max, down.x_mm, without.x_min, without.x_max);
  // Both fronts within two error bars of the measured ones (the downstream front falls 2.3 bars
  // behind without the added mass, 3.6 without the crowding factor, 6.7 with standard drag alone).
  EXPECT_LT(bars(with.x_min, up), 2.0);
  EXPECT_LT(bars(with.x_max, down), 2.0);
  // The curtain has spread, and the added mass spreads it further downstream (Ling et al.
  // 2012: the unsteady forces drive the downstream front).
  EXPECT_GT(with.x_max - with.x_min, 0.6 * (down.x_mm - up.x_mm));
  EXPECT_GT(with.x_max - without.x_max, 0.4);
}
