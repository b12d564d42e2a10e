// ParcelSystem mechanics: sub-stepping API, external force parts, temperature, and the
// contact history surviving neighbour rebuilds and re-sorting.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"

using namespace dustlift;

namespace {

DemConfig open_space() {
  DemConfig c;
  c.enabled = true;
  c.domain = DemDomain{-0.01, 0.01, -0.01, 0.01, false, false, false, false, false};
  return c;
}

}  // namespace

TEST(DemParcelSystem, AdvanceSubCyclesWithEquation18AndCallsTheHookEachSubStep) {
  ParcelSystem s(open_space());
  ParcelInit p;
  p.n_real = 15000.0;
  s.add_parcel(p);
  const double m = 980.0 * sphere_volume(100e-6);
  // Eq. (18): nu sqrt(m / max k) with the real-particle mass.
  EXPECT_NEAR(s.stable_time_step(), 0.1 * std::sqrt(m / 5e4), 1e-20);
  EXPECT_NEAR(s.stable_time_step(), 1.013e-8, 0.001e-8);
  const double F = 1e-9, Q = 1e-6;  // N and W per real particle
  int calls = 0;
  const double dt_cfd = 4.1e-7;  // a paper-like CFD step
  s.external_forces = true;
  s.integrate_temperature = true;
  const int n = s.advance(dt_cfd, [&](ParcelSystem& sys, double) {
    ++calls;
    sys.drag_fx[0] = F;       // the coupling's parts: drag + Magnus + pressure in x
    sys.magnus_fy[0] = 2 * F;
    sys.pressure_fy[0] = -F;
    sys.heat_rate[0] = Q;
  });
  EXPECT_EQ(n, static_cast<int>(std::ceil(dt_cfd / s.stable_time_step())));
  EXPECT_EQ(calls, n);
  EXPECT_DOUBLE_EQ(s.time(), dt_cfd);
  // Constant force: symplectic Euler gives the exact velocity F t / m_real.
  EXPECT_NEAR(s.vx[0], F / m * dt_cfd, 1e-12 * F / m * dt_cfd);
  EXPECT_NEAR(s.vy[0], F / m * dt_cfd, 1e-12 * F / m * dt_cfd);
  // Eq. (7): m c dT/dt = Q.
  // (up to the round-off of adding n small increments to 300 K: n ulp(300) = n 5.7e-14)
  EXPECT_NEAR(s.temperature[0] - 300.0, Q * dt_cfd / (m * 1200.0), n * 6e-14);
  // With external_forces off the parts are ignored (a DEM-only run).
  s.external_forces = false;
  const double v_before = s.vx[0];
  s.step(s.stable_time_step());
  EXPECT_EQ(s.vx[0], v_before);
}

TEST(DemParcelSystem, GravityAcceleratesEveryParcelAlike) {
  DemConfig c = open_space();
  c.gravity_y = -9.81;
  ParcelSystem s(c);
  ParcelInit p;
  s.add_parcel(p);
  p.x = 0.005;
  p.n_real = 7.0;
  s.add_parcel(p);
  const double dt = s.stable_time_step();
  for (int k = 0; k < 100; ++k) s.step(dt);
  EXPECT_NEAR(s.vy[0], -9.81 * 100 * dt, 1e-12);
  EXPECT_EQ(s.vy[0], s.vy[1]);
}

TEST(DemParcelSystem, ContactHistorySurvivesRebuildsAndResorting) {
  // A dense, agitated pack in a closed box (walls, no periodic wrap, so positions compare
  // bit for bit): the run that rebuilds the list (and re-sorts the parcels) every step must
  // match the one that rebuilds rarely, which needs every pair's and every wall's
  // tangential elongation carried over by id.
  auto run = [](bool rebuild_every_step) {
    DemConfig c = open_space();
    c.contact = ContactParams{5e4, 100.0, 1e-4, 0.5};
    c.wall_contact = c.contact;
    c.domain = DemDomain{0.0, 0.003, 0.0, 0.002, true, true, true, true, false};
    c.layer = LayerConfig{0.0, 0.003, 0.0, 0.002, 0.7, 8, LayerArrangement::JitteredLattice, false};
    ParcelSystem s = make_layer_system(c);
    std::uint64_t seed = 99;
    for (std::size_t i = 0; i < s.size(); ++i) {
      s.vx[i] = 4.0 * (uniform_from_seed(seed) - 0.5);
      s.vy[i] = 4.0 * (uniform_from_seed(seed) - 0.5);
    }
    const double dt = s.stable_time_step();
    for (int n = 0; n < 3000; ++n) {
      if (rebuild_every_step) s.invalidate_neighbours();
      s.step(dt);
    }
    std::vector<double> out(3 * s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      out[3 * s.id[i]] = s.x[i];
      out[3 * s.id[i] + 1] = s.y[i];
      out[3 * s.id[i] + 2] = s.omega[i];
    }
    return std::make_pair(out, s.neighbour_rebuilds());
  };
  const auto [rare, n_rare] = run(false);
  const auto [every, n_every] = run(true);
  EXPECT_LT(n_rare, 100);
  EXPECT_EQ(n_every, 3000);
  ASSERT_EQ(rare.size(), every.size());
  std::size_t differing = 0;
  double max_omega = 0.0;
  for (std::size_t k = 0; k < rare.size(); ++k) {
    differing += (rare[k] != every[k]);
    if (k % 3 == 2) max_omega = std::max(max_omega, std::fabs(rare[k]));
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(max_omega, 1.0);  // the tangential contacts did act
}
