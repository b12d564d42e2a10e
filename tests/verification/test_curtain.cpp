// The shock-particle-curtain validation case (cases/validation/curtain_ms166.toml, docs/
// validation.md) with its recommended physics, as the scene stands, on a reduced channel: the
// curtain's fronts 240 us after the shock against the measured ones (Wagner et al. 2012, as
// plotted by Ling et al. 2012, Fig. 14), and the forces that move it. The added mass of the
// resolved flow is a small part once the shock has crossed the curtain (the gas there is not
// accelerating: its pressure gradient is balanced by the drag). The downstream front's remaining
// gap (docs/validation.md: about 3 mm at 240 us with this physics) is why the bound there is
// four error bars; a drag or force that regressed moves the fronts by more.
#include <gtest/gtest.h>

#include <algorithm>
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

/// The fronts (mm from the curtain's upstream edge, x = 0) at t (s) on a 4 mm channel with the
/// scene's physics, and the largest |summed added-mass force| / |summed pressure-gradient force|
/// over the steps after 20 us (the shock has crossed the 2 mm curtain by 3.5 us).
struct CurtainRun {
  ParcelFronts fronts;
  double added_mass_share = 0.0;
};
CurtainRun run_to(double t, std::vector<std::string> overrides = {}) {
  for (const char* o : {"grid.y.end=0.004", "grid.y.cells=16", "particles.layer.y_max=0.004"})
    overrides.emplace_back(o);
  const Scene scene = load_scene(kCase, overrides);
  Simulation sim(scene);
  const ParcelSystem& p = *sim.parcels();
  CurtainRun r;
  while (sim.time() < t) {
    sim.advance(t - sim.time());
    const ParcelColumn am = p.find_part(ForcePart::AddedMass, 0);
    const ParcelColumn pr = p.find_part(ForcePart::Pressure, 0);
    if (sim.time() < 20e-6 || !am.valid() || !pr.valid()) continue;
    double sum_am = 0.0, sum_p = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      sum_am += p.n_real[k] * p.column(am)[k];
      sum_p += p.n_real[k] * p.column(pr)[k];
    }
    r.added_mass_share = std::max(r.added_mass_share, std::abs(sum_am) / std::abs(sum_p));
  }
  std::vector<std::size_t> order;
  r.fronts = parcel_fronts(p.x, p.n_real, 0.01, order);
  for (double* x : {&r.fronts.x_min, &r.fronts.x_max, &r.fronts.x_low, &r.fronts.x_high}) *x *= 1e3;
  return r;
}

/// |ours - measured| in units of the error bar on that side.
double bars(double ours, const Measured& m) {
  const double d = ours - m.x_mm;
  return std::abs(d) / (d >= 0.0 ? m.plus_mm : m.minus_mm);
}

}  // namespace

TEST(Curtain, RecommendedPhysicsFrontsAndForcesAfter240us) {
  const Measured up = measured("upstream", 240.0), down = measured("downstream", 240.0);
  ASSERT_NEAR(up.t_us, 240.8, 0.5);
  ASSERT_NEAR(down.t_us, 240.8, 0.5);
  const CurtainRun r = run_to(down.t_us * 1e-6);
  const ParcelFronts& f = r.fronts;
  std::printf(
      "t = %.1f us: upstream %.2f mm (measured %.2f), downstream %.2f mm (measured %.2f); summed "
      "added-mass force at most %.3f of the summed pressure-gradient force after 20 us\n",
      down.t_us, f.x_min, up.x_mm, f.x_max, down.x_mm, r.added_mass_share);
  EXPECT_LT(bars(f.x_min, up), 2.0);
  EXPECT_LT(bars(f.x_max, down), 4.0);
  // The curtain has spread (standard drag alone spreads it to 6 mm by 240 us, the measured 11).
  EXPECT_GT(f.x_max - f.x_min, 0.5 * (down.x_mm - up.x_mm));
  // The added mass of the resolved flow is no compensation: under a fifth of the pressure force.
  EXPECT_GT(r.added_mass_share, 0.0);
  EXPECT_LT(r.added_mass_share, 0.2);
}
