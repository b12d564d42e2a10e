// Resting layers stay at rest: the paper's 60,000-parcel layer (not in contact, no
// gravity, as in the paper) and a small bed settled under gravity (contacts loaded).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/contact.hpp"

using namespace dustlift;

TEST(DemRestingLayer, PaperLayerOfSixtyThousandParcelsStaysAtRestFor10000Steps) {
  DemConfig c;  // paper defaults: 400 x 2 mm, 100 um, alpha_p 0.59, Table 2 contacts
  c.enabled = true;
  c.domain = DemDomain{0.0, 0.4, -0.002, 0.02, true, false, false, false, true};
  ParcelSystem s = make_layer_system(c);
  ASSERT_NEAR(static_cast<double>(s.size()) / 60000.0, 1.0, 0.02);
  const std::vector<double> x0 = s.x, y0 = s.y;
  const double dt = s.stable_time_step();
  double ke_max = 0.0;
  for (int n = 0; n < 10000; ++n) {
    s.step(dt);
    if (n % 100 == 99) ke_max = std::max(ke_max, s.kinetic_energy());
  }
  // No spurious force from walls, periodic images or list rebuilds: exactly at rest.
  EXPECT_LE(ke_max, 1e-30);
  EXPECT_EQ(s.contact_pair_count(), 0u);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    moved += (s.x[i] != x0[s.id[i]] || s.y[i] != y0[s.id[i]]);
  EXPECT_EQ(moved, 0u);
  std::printf("paper layer: %zu parcels, 10,000 steps of %.3e s, max KE %.3e J/m\n", s.size(), dt,
              ke_max);
}

TEST(DemRestingLayer, BedSettledUnderGravityStaysAtRest) {
  // 1 mm grains (cheap steps), restitution 0.3 so that the bed settles quickly.
  constexpr double d = 1e-3;
  DemConfig c;
  c.enabled = true;
  c.particle_diameter = c.parcel_diameter = d;
  const double m = c.density * sphere_volume(d);
  c.layer = LayerConfig{0.0, 0.02, 0.0, 0.01, 0.5, 4, LayerArrangement::JitteredLattice, false};
  c.domain = DemDomain{0.0, 0.02, 0.0, 0.03, true, false, false, false, true};
  c.real_per_parcel = 1.0;
  c.contact = ContactParams{5e4, 100.0, damping_for_restitution(m / 2, 5e4, 0.3), 0.5};
  c.wall_contact = c.contact;
  ParcelSystem s = make_layer_system(c);
  const double weight_work = m * 9.81 * d;  // J, one grain falling one diameter
  const double t_settle = settle_under_gravity(s, 9.81, 1e-8 * weight_work, 1.0);
  ASSERT_LT(t_settle, 1.0);
  ASSERT_GT(s.contact_pair_count(), s.size());  // a packed bed: more contacts than grains
  s.set_gravity(0.0, -9.81);
  const double dt = s.stable_time_step();
  double ke_max = 0.0;
  for (int n = 0; n < 10000; ++n) {
    s.step(dt);
    ke_max = std::max(ke_max, s.kinetic_energy());
  }
  const double bound = 1e-6 * weight_work * static_cast<double>(s.size());
  EXPECT_LT(ke_max, bound);
  std::printf(
      "settled bed: %zu grains, settled in %.3f s, %zu contacts, max KE over 10,000 steps "
      "%.3e J = %.2e of N m g d\n",
      s.size(), t_settle, s.contact_pair_count(), ke_max,
      ke_max / (weight_work * static_cast<double>(s.size())));
}
