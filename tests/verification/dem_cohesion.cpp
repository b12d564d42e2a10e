// Van der Waals cohesion in the DEM (docs/dem.md, "Cohesion") against the law's closed forms:
// a pair and a wall contact come to rest at the overlap F_c / k_n, a pair pulled apart
// quasi-statically lets go at the pull-off force F_c, and across a gap within the cut-off the
// force is the Hamaker tail; the same per real particle in parcels of any count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/cohesion.hpp"
#include "solver/laws/contact.hpp"

using namespace dustlift;

namespace {

constexpr double kD = 40e-6, kDensity = 1300.0, kKn = 2e4;
const double kMass = kDensity * sphere_volume(kD);

/// 40 um coal with A = 1e-19 J (F_c = 1.04e-6 N a pair, 2.08e-6 N at a wall), strongly damped
/// (e = 0.3) so that contacts come to rest quickly; floor at y = 0, no other wall.
DemConfig cohesive(double wall_factor = 1.0) {
  DemConfig c;
  c.enabled = true;
  c.density = kDensity;
  c.contact = ContactParams{kKn, 40.0, 0.0, 0.5};
  c.contact.restitution = 0.3;
  c.contact.damping = damping_for_restitution(0.5 * kMass, kKn, 0.3);
  c.wall_contact = c.contact;
  c.cohesion.hamaker = 1e-19;
  c.wall_cohesion = c.cohesion;
  c.wall_cohesion.hamaker *= wall_factor;
  c.domain = DemDomain{-0.001, 0.001, 0.0, 0.002, true, false, false, false, false};
  c.parcel_diameter = 4.0 * kD;
  return c;
}

ParcelInit parcel(double x, double y, double n, double D) {
  ParcelInit p;
  p.x = x;
  p.y = y;
  p.diameter = D;
  p.real_diameter = kD;
  p.density = kDensity;
  p.n_real = n;
  return p;
}

const double kPairPullOff = pull_off_force(CohesionParams{1e-19}, reduced_radius(0.5 * kD, 0.5 * kD));

/// Index of the parcel with id `id`.
std::size_t index_of(const ParcelSystem& s, int id) { return s.id[0] == id ? 0 : 1; }

}  // namespace

TEST(DemCohesion, PairAndWallComeToRestAtTheOverlapOfThePullOffForce) {
  for (double n : {1.0, 37.0}) {
    DemConfig cfg = cohesive();
    cfg.domain.wall_bottom = false;
    const double D = n == 1.0 ? kD : 3.0 * kD;
    ParcelSystem pair(cfg);
    // Touching by a hair: the cohesion pulls them in, the spring stops them at F_c / k_n.
    pair.add_parcel(parcel(-0.5 * D * (1 - 1e-9), 0.001, n, D));
    pair.add_parcel(parcel(0.5 * D * (1 - 1e-9), 0.001, n, D));
    const double dt = pair.stable_time_step();
    for (int k = 0; k < 20000; ++k) pair.step(dt);
    const double overlap = D - std::abs(pair.x[1] - pair.x[0]);
    const double expected = resting_overlap(kPairPullOff, kKn);
    std::printf("n = %g: pair overlap %.6e m, F_c / k_n = %.6e m\n", n, overlap, expected);
    EXPECT_NEAR(overlap / expected, 1.0, 1e-6);
    EXPECT_LT(std::abs(pair.vx[0]), 1e-9);

    cfg.domain.wall_bottom = true;
    ParcelSystem wall(cfg);
    wall.add_parcel(parcel(0.0, 0.5 * D * (1 - 1e-9), n, D));
    for (int k = 0; k < 20000; ++k) wall.step(wall.stable_time_step());
    const double wall_overlap = 0.5 * D - wall.y[0];
    const double wall_expected = resting_overlap(pull_off_force(cfg.wall_cohesion, 0.5 * kD), kKn);
    std::printf("n = %g: wall overlap %.6e m, F_c / k_n = %.6e m\n", n, wall_overlap, wall_expected);
    EXPECT_NEAR(wall_overlap / wall_expected, 1.0, 1e-6);
  }
}

TEST(DemCohesion, PairPulledApartQuasiStaticallyLetsGoAtThePullOffForce) {
  // Parcel 0 is held on the floor by a wall cohesion ten times the pair's; parcel 1 rests on
  // it. A body force pulling both up grows slowly, g(t) = rate t: parcel 1 lets go when its
  // real particles' weight m g reaches F_c (per real particle, whatever the count).
  for (double n : {1.0, 37.0}) {
    const double D = n == 1.0 ? kD : 3.0 * kD;
    ParcelSystem s(cohesive(10.0));
    // Touching by a hair, so that the cohesion acts from the start.
    s.add_parcel(parcel(0.0, 0.5 * D * (1 - 1e-9), n, D));
    s.add_parcel(parcel(0.0, 1.5 * D * (1 - 1e-9), n, D));
    const double dt = s.stable_time_step();
    // Settle first, then ramp over ~4,000 contact times.
    for (int k = 0; k < 20000; ++k) s.step(dt);
    const double g_pull_off = kPairPullOff / kMass;
    const double ramp_time = 4000.0 * contact_duration(0.5 * kMass, kKn, s.config().contact.damping);
    const double rate = 1.5 * g_pull_off / ramp_time;
    double g = 0.0, g_released = -1.0;
    for (long k = 0; k < 10000000 && g_released < 0.0; ++k) {
      g = rate * static_cast<double>(k) * dt;
      s.set_gravity(0.0, g);
      s.step(dt);
      const std::size_t a = index_of(s, 0), b = index_of(s, 1);
      if (s.y[b] - s.y[a] > D) g_released = g;
    }
    std::printf("n = %g: released at m g = %.6e N, F_c = %.6e N (%.2e relative)\n", n,
                g_released * kMass, kPairPullOff, g_released * kMass / kPairPullOff - 1.0);
    EXPECT_NEAR(g_released * kMass / kPairPullOff, 1.0, 2e-3);
    // The floor held parcel 0.
    EXPECT_LT(s.y[index_of(s, 0)], 0.5 * D);
  }
}

TEST(DemCohesion, AcrossAGapTheTailActsUpToTheCutOff) {
  DemConfig cfg = cohesive();
  cfg.domain.wall_bottom = false;
  cfg.cohesion.cutoff = 1e-6;
  cfg.wall_cohesion.cutoff = 1e-6;
  const double gap = 2e-9;
  ParcelSystem s(cfg);
  s.add_parcel(parcel(-0.5 * (kD + gap), 0.001, 1.0, kD));
  s.add_parcel(parcel(0.5 * (kD + gap), 0.001, 1.0, kD));
  s.step(1e-15);
  const double expected = van_der_waals_force(cfg.cohesion, reduced_radius(0.5 * kD, 0.5 * kD), gap);
  const std::size_t a = index_of(s, 0), b = index_of(s, 1);
  EXPECT_NEAR(s.contact_fx[a] / expected, 1.0, 1e-6);  // towards parcel 1 (+x)
  EXPECT_NEAR(s.contact_fx[b] / -expected, 1.0, 1e-6);
  EXPECT_NEAR(expected / kPairPullOff, std::pow(4e-10 / gap, 2), 1e-6);
  // Beyond the cut-off nothing.
  ParcelSystem far(cfg);
  far.add_parcel(parcel(-0.5 * (kD + 2e-6), 0.001, 1.0, kD));
  far.add_parcel(parcel(0.5 * (kD + 2e-6), 0.001, 1.0, kD));
  far.step(1e-15);
  EXPECT_EQ(far.contact_fx[0], 0.0);
}
