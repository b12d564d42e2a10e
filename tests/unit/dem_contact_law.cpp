// Closed-form spring–dashpot relations and the contact kernel (docs/dem.md).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solver/dem/coarse_graining.hpp"
#include "solver/laws/contact.hpp"

using namespace dustlift;

namespace {
const double kMass = 980.0 * sphere_volume(100e-6);  // 5.13127e-10 kg
}

TEST(DemContactLaw, PaperParametersGiveReferenceRestitutionAndDuration) {
  EXPECT_NEAR(kMass, 5.13127e-10, 1e-15);
  // Pair: m_eff = m/2; wall: m_eff = m (§3.7 table).
  EXPECT_NEAR(contact_damping_ratio(kMass / 2, 5e4, 1e-4), 0.01396, 1e-5);
  EXPECT_NEAR(contact_restitution(kMass / 2, 5e4, 1e-4), 0.957, 5e-4);
  EXPECT_NEAR(contact_restitution(kMass, 5e4, 1e-4), 0.969, 5e-4);
  EXPECT_NEAR(contact_duration(kMass / 2, 5e4, 1e-4), 2.25e-7, 0.01e-7);
  EXPECT_NEAR(contact_duration(kMass, 5e4, 1e-4), 3.18e-7, 0.01e-7);
}

TEST(DemContactLaw, DampingForRestitutionInvertsRestitution) {
  for (double e : {0.1, 0.5, 0.9, 0.957}) {
    const double h = damping_for_restitution(kMass / 2, 5e4, e);
    EXPECT_NEAR(contact_restitution(kMass / 2, 5e4, h), e, 1e-12);
  }
  // §3.7: e = 0.9 needs h = 2.40e-4, e = 0.5 needs 1.54e-3 (pair).
  EXPECT_NEAR(damping_for_restitution(kMass / 2, 5e4, 0.9), 2.40e-4, 0.01e-4);
  EXPECT_NEAR(damping_for_restitution(kMass / 2, 5e4, 0.5), 1.54e-3, 0.01e-3);
}

TEST(DemContactLaw, ForcePushesApartAndTangentialActsAlongSlip) {
  ContactParams p{5e4, 100.0, 1e-4, std::numeric_limits<double>::infinity()};
  // Partner to the right (+x), approaching (u_n < 0), its surface sliding up (+y = +t).
  const auto c = contact_force(p, 1.0, 0.0, 1e-8, -1.0, 0.5, 2e-9, 5e-5, 1e-9);
  EXPECT_DOUBLE_EQ(c.fx, -5e4 * 1e-8 + 1e-4 * -1.0);
  EXPECT_DOUBLE_EQ(c.fy, 100.0 * 2e-9 + 1e-4 * 0.5);
  EXPECT_DOUBLE_EQ(c.torque, 5e-5 * c.fy);  // n x F_t = +z F_t for n = x
  EXPECT_DOUBLE_EQ(c.delta_t, 2e-9 + 0.5 * 1e-9);
}

TEST(DemContactLaw, CoulombLimitCapsTangentialForce) {
  ContactParams p{5e4, 100.0, 1e-4, 0.3};
  const auto c = contact_force(p, 0.0, 1.0, 1e-8, 10.0, 0.0, 0.0, 5e-5, 1e-9);
  // n = +y, t = (-1, 0): u_t = -10, F_n = -5e-4 N along n.
  EXPECT_NEAR(c.fy, -5e-4, 1e-18);
  EXPECT_NEAR(std::fabs(c.fx), 0.3 * 5e-4, 1e-18);
  EXPECT_GT(c.fx, 0.0);  // F_t = -1.5e-4 t = +1.5e-4 x: along the partner's slip
  // The elongation grows by u_t dt but the spring alone never exceeds the Coulomb force.
  EXPECT_DOUBLE_EQ(c.delta_t, -10.0 * 1e-9);
  const auto held = contact_force(p, 0.0, 1.0, 1e-8, 10.0, 0.0, -1e-5, 5e-5, 1e-9);
  EXPECT_DOUBLE_EQ(held.delta_t, -0.3 * 5e-4 / 100.0);
}
