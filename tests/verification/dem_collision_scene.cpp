// A single collision set up from a scene: cases/verification/two_parcel_collision.toml places
// two parcels with a layer file (arrangement = "file") and switches every gas effect off, so
// the run through the scene path (parser, CSV reader, Simulation with its gas, DEM
// sub-cycling) must give the restitution of the spring-dashpot formula.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/dem/coarse_graining.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"

using namespace dustlift;

TEST(DemCollisionScene, HeadOnPairFromALayerFileReboundsWithTheSpringDashpotRestitution) {
  const Scene scene = load_scene(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/two_parcel_collision.toml");
  ASSERT_EQ(scene.particles.layer_parcels.size(), 2u);
  Simulation sim(scene);
  const ParcelSystem& p = *sim.parcels();
  auto velocity_of = [&](int id) {
    for (std::size_t k = 0; k < p.size(); ++k)
      if (p.id[k] == id) return p.vx[k];
    return std::nan("");
  };
  const double v0 = velocity_of(0), v1 = velocity_of(1);
  sim.run("");
  const double e = (velocity_of(1) - velocity_of(0)) / (v0 - v1);

  // docs/dem.md with the real-particle mass: m_eff = m/2.
  const auto& c = scene.particles.contact;
  const double m = scene.particles.density * sphere_volume(scene.particles.particle_diameter);
  const double zeta = c.damping / (2.0 * std::sqrt(0.5 * m * c.k_n));
  const double e_formula = std::exp(-std::numbers::pi * zeta / std::sqrt(1.0 - zeta * zeta));
  std::printf("two_parcel_collision.toml: e_n = %.6f vs formula %.6f (%+.2e relative), %lld CFD steps\n", e, e_formula,
              e / e_formula - 1.0, sim.step());
  EXPECT_NEAR(e_formula, 0.957087, 1e-6);
  EXPECT_NEAR(e / e_formula, 1.0, 1e-3);
  // Head-on: nothing vertical or rotational, and momentum conserved.
  for (std::size_t k = 0; k < p.size(); ++k) {
    EXPECT_EQ(p.vy[k], 0.0);
    EXPECT_EQ(p.omega[k], 0.0);
  }
  EXPECT_NEAR(velocity_of(0) + velocity_of(1), 0.0, 1e-12);
}
