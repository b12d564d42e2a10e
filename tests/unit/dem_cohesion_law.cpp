// The van der Waals cohesion law (solver/laws/cohesion.hpp) against its closed forms, and the
// restitution-following dashpot (solver/laws/contact.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/laws/cohesion.hpp"
#include "solver/laws/contact.hpp"

using namespace dustlift;

TEST(CohesionLaw, SmoothSpheresPullOffIsHamakerOverSixSquaredSeparation) {
  // A = 1e-19 J, s0 = 0.4 nm, two 10 um spheres: R* = 2.5 um, F_c = A R*/(6 s0^2) = 2.604e-7 N,
  // equal to 2 pi W R* with W = A/(12 pi s0^2) (the DMT pull-off).
  CohesionParams c;
  c.hamaker = 1e-19;
  c.min_separation = 4e-10;
  const double r_star = reduced_radius(5e-6, 5e-6);
  EXPECT_DOUBLE_EQ(r_star, 2.5e-6);
  const double f = pull_off_force(c, r_star);
  EXPECT_NEAR(f, 1e-19 * 2.5e-6 / (6.0 * 1.6e-19), 1e-20);
  EXPECT_NEAR(f / 2.604e-7, 1.0, 2e-4);
  const double w = 1e-19 / (12.0 * std::numbers::pi * 1.6e-19);
  EXPECT_NEAR(f / (2.0 * std::numbers::pi * w * r_star), 1.0, 1e-14);
  // A sphere at a wall: R* = R, twice a pair of equal spheres.
  EXPECT_NEAR(pull_off_force(c, 5e-6) / f, 2.0, 1e-14);
  // Proportional to the size.
  EXPECT_NEAR(pull_off_force(c, reduced_radius(50e-6, 50e-6)) / f, 10.0, 1e-12);
}

TEST(CohesionLaw, SurfaceEnergyAndHamakerConstantAreOneLaw) {
  const double s0 = 4e-10;
  const double gamma = surface_energy_of_hamaker(1e-19, s0);
  EXPECT_NEAR(gamma, 8.29e-3, 1e-5);  // A / (24 pi s0^2)
  EXPECT_NEAR(hamaker_of_surface_energy(gamma, s0), 1e-19, 1e-33);
  CohesionParams c;
  c.hamaker = hamaker_of_surface_energy(gamma, s0);
  // F_c = 4 pi gamma R* (DMT with W = 2 gamma).
  EXPECT_NEAR(pull_off_force(c, 3e-6) / (4.0 * std::numbers::pi * gamma * 3e-6), 1.0, 1e-13);
}

TEST(CohesionLaw, AsperitiesFollowRumpfAndTheTailIsContinuous) {
  CohesionParams c;
  c.hamaker = 1e-19;
  c.asperity_radius = 0.1e-6;
  const double r_star = 10e-6, s0 = c.min_separation, a = c.asperity_radius;
  // Rumpf: the asperity touching (a R*/(a + R*) at s0) and the bodies at s0 + a.
  const double rumpf = 1e-19 / 6.0 * (a * r_star / ((a + r_star) * s0 * s0) + r_star / ((s0 + a) * (s0 + a)));
  EXPECT_NEAR(pull_off_force(c, r_star) / rumpf, 1.0, 1e-14);
  // For a << R* about A a / (6 s0^2), nearly independent of the size: 1.03e-8 N here.
  EXPECT_NEAR(pull_off_force(c, r_star), 1e-19 * a / (6 * s0 * s0), 0.02e-8);
  EXPECT_LT(pull_off_force(c, r_star), 0.02 * pull_off_force(CohesionParams{1e-19}, r_star));
  // Without a cut-off nothing acts across a gap; with one the tail starts at the contact value
  // and falls as 1/s^2 for smooth spheres.
  CohesionParams smooth{1e-19};
  EXPECT_EQ(van_der_waals_force(smooth, r_star, 1e-9), 0.0);
  smooth.cutoff = 1e-6;
  EXPECT_EQ(van_der_waals_force(smooth, r_star, 0.5 * s0), pull_off_force(smooth, r_star));
  EXPECT_NEAR(van_der_waals_force(smooth, r_star, 2.0 * s0) / pull_off_force(smooth, r_star), 0.25,
              1e-14);
  EXPECT_EQ(van_der_waals_force(smooth, r_star, 1e-6), 0.0);
  c.cutoff = 1e-6;
  EXPECT_NEAR(van_der_waals_force(c, r_star, s0 * (1.0 + 1e-12)) / pull_off_force(c, r_star), 1.0,
              1e-11);
}

TEST(CohesionLaw, RestingOverlapAndBondNumber) {
  EXPECT_DOUBLE_EQ(resting_overlap(2e-6, 2e4), 1e-10);
  // 40 um coal (1300 kg/m^3) at A = 1e-19 J: F_c = 1.042e-6 N, m g = 4.275e-10 N.
  CohesionParams c{1e-19};
  const double m = 1300.0 * std::numbers::pi * std::pow(40e-6, 3) / 6.0;
  EXPECT_NEAR(bond_number(pull_off_force(c, 10e-6), m, 9.81), 2437.0, 1.0);
}

TEST(RestitutionDashpot, FactorGivesTheRestitutionForAnyMass) {
  for (double e : {0.3, 0.9, 0.957}) {
    for (double m_eff : {1e-13, 2.18e-11, 4e-9}) {
      const double h = pair_damping(restitution_damping_factor(e), m_eff, 2e4);
      EXPECT_NEAR(contact_restitution(m_eff, 2e4, h), e, 1e-13) << e << " " << m_eff;
      EXPECT_NEAR(h / damping_for_restitution(m_eff, 2e4, e), 1.0, 1e-14);
    }
  }
  EXPECT_EQ(restitution_damping_factor(1.0), 0.0);
}

TEST(RestitutionDashpot, PairMassUnderThePairRule) {
  // Equal counts: the real particles' reduced mass.
  EXPECT_DOUBLE_EQ(pair_effective_mass(1.0 / 2.0, 1.0 / 6.0, 7.0, 7.0), 1.5);
  // Parcels of n_i = 10 particles of 1 kg and n_j = 2 of 5 kg: the pair is 2 real contacts on
  // parcels of 10 kg each, M* = 5 kg, per contact 2.5 kg; never below the real 5/6 kg.
  EXPECT_DOUBLE_EQ(pair_effective_mass(1.0, 0.2, 10.0, 2.0), 2.5);
  EXPECT_DOUBLE_EQ(pair_effective_mass(0.2, 1.0, 2.0, 10.0), 2.5);
  EXPECT_GE(pair_effective_mass(1.0, 0.2, 10.0, 2.0), 1.0 / (1.0 + 0.2));
}
