// The restitution a scene gives is the material's (docs/dem.md, "Restitution"): head-on
// collisions of pairs of coal particles of the coal scene's smallest (16.5 um) and largest
// (97.2 um) classes, of parcels of different real counts, and at the wall, all rebound with
// e = 0.9 within the integration error, where one dashpot for every size gives 0.67 to 0.97.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/contact.hpp"

using namespace dustlift;

namespace {

constexpr double kDensity = 1300.0, kKn = 2e4, kE = 0.9;
constexpr double kSmall = 16.4541e-6, kLarge = 97.2401e-6, kMedian = 40e-6;

double mass_of(double d) { return kDensity * sphere_volume(d); }

/// The coal scene's contacts, with the restitution given (per material) or only the dashpot
/// that gives it between two median particles (the scene's `damping = 4.4e-5`).
DemConfig coal(bool per_material, double courant = 0.1) {
  DemConfig c;
  c.enabled = true;
  const double h = damping_for_restitution(0.5 * mass_of(kMedian), kKn, kE);
  c.contact = ContactParams{kKn, 40.0, h, std::numeric_limits<double>::infinity()};
  c.contact.restitution = per_material ? kE : 0.0;
  c.wall_contact = c.contact;
  c.wall_contact.damping = damping_for_restitution(mass_of(kMedian), kKn, kE);
  c.domain = DemDomain{-0.01, 0.01, 0.0, 0.01, true, false, false, false, false};
  c.density = kDensity;
  c.courant = courant;  // 0.1: the scenes' default
  c.parcel_diameter = 2.0 * kLarge;
  return c;
}

ParcelInit parcel(double x, double y, double vx, double vy, double d, double n, double D) {
  ParcelInit p;
  p.x = x;
  p.y = y;
  p.vx = vx;
  p.vy = vy;
  p.diameter = D;
  p.real_diameter = d;
  p.density = kDensity;
  p.n_real = n;
  return p;
}

/// Head-on impact of two parcels (real diameters d0, d1, counts n0, n1, parcel diameters D0,
/// D1) at 1 m/s each: the ratio of the separation speed after to the approach speed before.
double pair_restitution(const DemConfig& cfg, double d0, double n0, double D0, double d1,
                        double n1, double D1) {
  ParcelSystem s(cfg);
  const double gap = 0.5 * (D0 + D1) * 1.01;
  s.add_parcel(parcel(-0.5 * gap, 0.005, 1.0, 0.0, d0, n0, D0));
  s.add_parcel(parcel(0.5 * gap, 0.005, -1.0, 0.0, d1, n1, D1));
  const double dt = s.stable_time_step();
  auto speed = [&] {  // of parcel 1 away from parcel 0 (ids 0 and 1)
    const bool in_order = s.id[0] == 0;
    const std::size_t a = in_order ? 0 : 1, b = in_order ? 1 : 0;
    return s.vx[b] - s.vx[a];
  };
  auto touching = [&] { return std::abs(s.x[1] - s.x[0]) < 0.5 * (D0 + D1); };
  const double before = speed();
  bool touched = false;
  for (int k = 0; k < 1000000 && !(touched && !touching()); ++k) {
    s.step(dt);
    touched = touched || touching();
  }
  return -speed() / before;
}

/// A parcel falling onto the floor at 1 m/s: its rebound speed over its impact speed.
double wall_restitution(const DemConfig& cfg, double d, double n, double D) {
  ParcelSystem s(cfg);
  s.add_parcel(parcel(0.0, 0.51 * D, 0.0, -1.0, d, n, D));
  const double dt = s.stable_time_step();
  bool touched = false;
  for (int k = 0; k < 1000000 && !(touched && s.y[0] > 0.5 * D); ++k) {
    s.step(dt);
    touched = touched || s.y[0] < 0.5 * D;
  }
  return s.vy[0];
}

}  // namespace

TEST(DemRestitution, PairsOfEverySizeReboundWithTheMaterialRestitution) {
  // At the scenes' DEM step (nu_DEM = 0.1, 22-31 sub-steps a contact) symplectic Euler misses
  // e by up to a few 1e-3, depending on where the contact starts within a step; at a fifth of
  // it the error falls below 1e-3: every pair converges to the material's 0.9.
  for (const double courant : {0.1, 0.02}) {
    const DemConfig cfg = coal(true, courant);
    // Real particles (one per parcel, parcel = particle).
    const double small = pair_restitution(cfg, kSmall, 1, kSmall, kSmall, 1, kSmall);
    const double large = pair_restitution(cfg, kLarge, 1, kLarge, kLarge, 1, kLarge);
    const double mixed = pair_restitution(cfg, kSmall, 1, kSmall, kLarge, 1, kLarge);
    // Parcels of the two classes at parcel ratio 2 holding different real counts (the pair
    // rule: min(n_i, n_j) real contacts).
    const double n_small = equal_fraction_real_per_parcel(2 * kSmall, kSmall);
    const double n_large = equal_fraction_real_per_parcel(2 * kLarge, kLarge);
    const double parcels =
        pair_restitution(cfg, kSmall, n_small, 2 * kSmall, kLarge, n_large, 2 * kLarge);
    std::printf("nu_DEM %.2f, e (material 0.9): 16.5-16.5 um %.6f, 97.2-97.2 um %.6f, "
                "16.5-97.2 um %.6f, parcels of %.0f and %.0f real particles %.6f\n",
                courant, small, large, mixed, n_small, n_large, parcels);
    const double tolerance = courant == 0.1 ? 6e-3 : 1e-3;
    for (double e : {small, large, mixed, parcels}) EXPECT_NEAR(e, kE, tolerance) << e;
  }
}

TEST(DemRestitution, WallImpactsOfEverySizeReboundWithTheMaterialRestitution) {
  for (const double courant : {0.1, 0.02}) {
    DemConfig cfg = coal(true, courant);
    cfg.wall_contact.restitution = kE;
    const double small = wall_restitution(cfg, kSmall, 1, kSmall);
    const double large = wall_restitution(cfg, kLarge, 1, kLarge);
    const double parcel = wall_restitution(cfg, kSmall, 200, 2 * kSmall);
    std::printf("nu_DEM %.2f, wall e (material 0.9): 16.5 um %.6f, 97.2 um %.6f, a 16.5 um "
                "parcel of 200 %.6f\n",
                courant, small, large, parcel);
    const double tolerance = courant == 0.1 ? 6e-3 : 1e-3;
    for (double e : {small, large, parcel}) EXPECT_NEAR(e, kE, tolerance) << e;
  }
}

TEST(DemRestitution, OneDashpotForEverySizeGivesEachSizeItsOwn) {
  // What the restitution replaces: the coal scene's one dashpot (0.9 between median particles).
  const DemConfig cfg = coal(false);
  const double small = pair_restitution(cfg, kSmall, 1, kSmall, kSmall, 1, kSmall);
  const double large = pair_restitution(cfg, kLarge, 1, kLarge, kLarge, 1, kLarge);
  std::printf("one dashpot: 16.5-16.5 um %.4f, 97.2-97.2 um %.4f\n", small, large);
  EXPECT_NEAR(small, contact_restitution(0.5 * mass_of(kSmall), kKn, cfg.contact.damping), 2e-3);
  EXPECT_NEAR(small, 0.670, 3e-3);
  EXPECT_NEAR(large, 0.973, 2e-3);
}
