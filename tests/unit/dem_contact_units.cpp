// The DEM's contact units (solver/dem/contact_effects/): the build finds every unit and orders
// them by kPosition, and a scene runs only the units its keys switch on (none without cohesion).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "solver/dem/contact_effects/cohesion.hpp"
#include "solver/dem/contact_summary.hpp"
#include "solver/dem/dem_config.hpp"

using namespace dustlift;

TEST(ContactUnits, EveryUnitOfTheBuildIsFoundInItsOrder) {
  // The build lists every `class <Name>Contact final` of contact_effects/ (contact_units.hpp),
  // ordered by kPosition: the order the contact pass adds their forces in.
  const std::vector<std::string> names = contact_unit_names();
  const std::vector<std::string> expected{CohesionContact::kName};
  EXPECT_EQ(names, expected);
}

TEST(ContactUnits, NoUnitIsActiveWithoutCohesion) {
  const DemConfig off;
  EXPECT_FALSE(CohesionContact::active(off));
  EXPECT_TRUE(contact_descriptions(off).empty());
  EXPECT_EQ(CohesionContact::pair_reach(off), 0.0);
  EXPECT_EQ(CohesionContact::wall_reach(off), 0.0);
}

TEST(ContactUnits, CohesionIsActiveForThePairsOrTheWallsAndReachesItsCutoff) {
  DemConfig c;
  c.cohesion.hamaker = 1e-19;
  c.cohesion.cutoff = 4e-10;
  const std::vector<std::string> lines = contact_descriptions(c);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind("cohesion: van der Waals", 0), 0u) << lines[0];
  EXPECT_EQ(CohesionContact::pair_reach(c), 4e-10);
  EXPECT_EQ(CohesionContact::wall_reach(c), 0.0);  // the wall's law is off
  DemConfig wall_only;
  wall_only.wall_cohesion.hamaker = 1e-19;
  wall_only.wall_cohesion.cutoff = 1e-9;
  EXPECT_TRUE(CohesionContact::active(wall_only));
  EXPECT_EQ(CohesionContact::pair_reach(wall_only), 0.0);
  EXPECT_EQ(CohesionContact::wall_reach(wall_only), 1e-9);
}

TEST(ContactUnits, CohesionAddsThePullOffWhileTouchingAndTheTailAcrossTheGap) {
  // The unit's forces are the law's (laws/cohesion.hpp) at the real particles' reduced radius.
  DemConfig cfg;
  cfg.cohesion.hamaker = 1e-19;
  cfg.cohesion.cutoff = 1e-8;
  cfg.wall_cohesion = cfg.cohesion;
  const CohesionContact u(cfg);
  const double diameters[] = {20e-6, 10e-6};
  const ContactColumns cols{diameters};
  const double r_star = reduced_radius(10e-6, 5e-6);
  double f = 0.0, dist = 0.0;
  ASSERT_TRUE(u.pair_touching(cols, 0, 1, f));
  EXPECT_EQ(f, pull_off_force(cfg.cohesion, r_star));
  const double rs = 30e-6, gap = 2e-9;
  ASSERT_TRUE(u.pair_gap(cols, 0, 1, (rs + gap) * (rs + gap), rs, f, dist));
  EXPECT_NEAR(f / van_der_waals_force(cfg.cohesion, r_star, gap), 1.0, 1e-6);
  EXPECT_FALSE(u.pair_gap(cols, 0, 1, (rs + 2e-8) * (rs + 2e-8), rs, f, dist));  // beyond
  ASSERT_TRUE(u.wall_touching(cols, 1, f));
  EXPECT_EQ(f, pull_off_force(cfg.wall_cohesion, 5e-6));
  EXPECT_FALSE(u.wall_gap(cols, 1, 2e-8, f));
  // The work held over an overlap: -weight F_c overlap.
  double e = 1.0;
  u.pair_energy(cols, 0, 1, 1e-9, 0.5, e);
  EXPECT_EQ(e, 1.0 - 0.5 * pull_off_force(cfg.cohesion, r_star) * 1e-9);
}
