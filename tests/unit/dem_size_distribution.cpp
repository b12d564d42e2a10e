// Polydisperse layers: the log-normal cut, the class counts and their shuffle, a packed
// layer's mass shares and volume fraction, and momentum in contacts between size classes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/dem/size_distribution.hpp"

using namespace dustlift;

TEST(SizeDistribution, NormalQuantileMatchesTabulatedValues) {
  // Abramowitz & Stegun, Table 26.5 (to 16 digits).
  EXPECT_NEAR(standard_normal_quantile(0.1), -1.2815515655446008, 1e-14);
  EXPECT_NEAR(standard_normal_quantile(0.3), -0.5244005127080407, 1e-14);
  EXPECT_EQ(standard_normal_quantile(0.5), 0.0);
  EXPECT_NEAR(standard_normal_quantile(0.975), 1.9599639845400536, 1e-14);
  EXPECT_NEAR(standard_normal_quantile(1e-6), -4.753424308822899, 1e-12);
}

TEST(SizeDistribution, LognormalCutGivesEqualMassClassesAtTheMassQuantiles) {
  // Mass median 50 um, sigma_g = 2, five classes: d_k = 50 um 2^z_k, z_k = Phi^-1((k + 1/2)/5)
  // = -1.28155, -0.52440, 0, 0.52440, 1.28155.
  const std::vector<SizeClass> c = lognormal_classes(50e-6, 2.0, 5);
  ASSERT_EQ(c.size(), 5u);
  const double expected[] = {20.567643787232293e-6, 34.762397416024104e-6, 50e-6,
                             71.91678899705571e-6, 121.5501408844856e-6};
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(c[k].diameter, expected[k], 1e-13 * expected[k]) << k;
    EXPECT_EQ(c[k].mass_fraction, 0.2);
  }
  // Symmetric in ln d about the median: d_0 d_4 = d_1 d_3 = median^2.
  EXPECT_NEAR(c[0].diameter * c[4].diameter, 50e-6 * 50e-6, 1e-12 * 2.5e-9);
  EXPECT_EQ(mass_median_diameter(c), c[2].diameter);
  EXPECT_EQ(mass_median_diameter({{10e-6, 0.3}, {20e-6, 0.15}, {30e-6, 0.55}}), 30e-6);
  EXPECT_THROW(lognormal_classes(50e-6, 1.0, 5), std::invalid_argument);
}

TEST(SizeDistribution, LargestRemainderCountsSumToTheTotal) {
  EXPECT_EQ(largest_remainder_counts(10, {0.33, 0.33, 0.34}), (std::vector<std::int64_t>{3, 3, 4}));
  // 3.5, 1.75, 1.75: floors 3, 1, 1; the two units left go to the 0.75 remainders.
  EXPECT_EQ(largest_remainder_counts(7, {0.5, 0.25, 0.25}), (std::vector<std::int64_t>{3, 2, 2}));
  // Ties go to the smaller class: 2.5, 2.5 -> 3, 2.
  EXPECT_EQ(largest_remainder_counts(5, {0.5, 0.5}), (std::vector<std::int64_t>{3, 2}));
  const std::vector<std::int64_t> c = largest_remainder_counts(60097, {0.2, 0.2, 0.2, 0.2, 0.2});
  EXPECT_EQ(std::accumulate(c.begin(), c.end(), std::int64_t{0}), 60097);
  EXPECT_EQ(c, (std::vector<std::int64_t>{12020, 12020, 12019, 12019, 12019}));
}

TEST(SizeDistribution, ShuffleIsDeterministicAndKeepsTheCounts) {
  const std::vector<std::int64_t> counts{3, 2, 5};
  const std::vector<int> a = shuffled_classes(counts, 7), b = shuffled_classes(counts, 7);
  EXPECT_EQ(a, b);
  // Pinned: std::mt19937_64's output is fixed by the standard and the bounded draw is ours, so
  // every platform gives these classes for seed 7.
  EXPECT_EQ(a, (std::vector<int>{0, 2, 1, 2, 1, 0, 0, 2, 2, 2}));
  EXPECT_NE(shuffled_classes(counts, 8), a);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(std::count(a.begin(), a.end(), k), counts[static_cast<std::size_t>(k)]);
}

TEST(SizeDistribution, PackedLognormalLayerHoldsTheAskedMassSharesAndVolumeFraction) {
  DemConfig cfg;
  cfg.enabled = true;
  cfg.size_classes = lognormal_classes(60e-6, 1.6, 5);
  cfg.particle_diameter = mass_median_diameter(cfg.size_classes);
  cfg.parcel_diameter = cfg.size_classes.back().diameter;
  cfg.layer.x_max = 0.05;
  cfg.domain.x_max = 0.05;
  const ParcelSystem ps = make_layer_system(cfg);
  ASSERT_GT(ps.size(), 5000u);
  std::vector<double> mass(5, 0.0);
  double total = 0.0, solid = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const auto k = static_cast<std::size_t>(ps.size_class[i]);
    EXPECT_EQ(ps.real_diameter[i], cfg.size_classes[k].diameter);
    mass[k] += ps.mass[i];
    total += ps.mass[i];
    solid += ps.n_real[i] * sphere_volume(ps.real_diameter[i]);
  }
  for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(mass[k] / total, 0.2, 0.02 * 0.2) << k;
  const double area = (cfg.layer.x_max - cfg.layer.x_min) * (cfg.layer.y_max - cfg.layer.y_min);
  EXPECT_NEAR(solid / area, 0.59, 0.02 * 0.59);
  // Every parcel holds the same solid volume, whatever its class.
  EXPECT_NEAR(ps.n_real[0] * sphere_volume(ps.real_diameter[0]),
              solid / static_cast<double>(ps.size()),
              1e-9 * solid / static_cast<double>(ps.size()));
  // The classes are spread over the layer, not in blocks: neighbours in placement order differ.
  int changes = 0;
  for (std::size_t i = 1; i < ps.size(); ++i) changes += ps.size_class[i] != ps.size_class[i - 1];
  EXPECT_GT(changes, static_cast<int>(ps.size()) / 2);
  // The stable step is the smallest real particle's (eq. 18).
  const double m_min = cfg.density * sphere_volume(cfg.size_classes.front().diameter);
  EXPECT_NEAR(ps.stable_time_step(), cfg.courant * std::sqrt(m_min / cfg.contact.k_n),
              1e-12 * ps.stable_time_step());
}

namespace {

/// Two parcels of one parcel diameter, different real particles, colliding obliquely with spin
/// in open space; returns their total momentum before and after and the largest velocity change.
struct Collision {
  double px0, py0, px1, py1, dv;
};
Collision collide(double n_a, double d_a, double n_b, double d_b) {
  DemConfig cfg;
  cfg.domain = {-0.01, 0.01, -0.01, 0.01, false, false, false, false, false};
  cfg.contact.friction = 0.3;
  ParcelSystem ps(cfg);
  ParcelInit a;
  a.x = -60e-6;
  a.y = 10e-6;
  a.vx = 1.0;
  a.vy = 0.2;
  a.omega = 3000.0;
  a.diameter = 100e-6;
  a.real_diameter = d_a;
  a.n_real = n_a;
  ParcelInit b = a;
  b.x = 60e-6;
  b.y = -10e-6;
  b.vx = -0.5;
  b.vy = 0.0;
  b.omega = -1000.0;
  b.real_diameter = d_b;
  b.n_real = n_b;
  b.size_class = 1;
  ps.add_parcel(a);
  ps.add_parcel(b);
  auto momentum = [&](double& px, double& py) {
    px = ps.mass[0] * ps.vx[0] + ps.mass[1] * ps.vx[1];
    py = ps.mass[0] * ps.vy[0] + ps.mass[1] * ps.vy[1];
  };
  Collision c{};
  momentum(c.px0, c.py0);
  const double dt = ps.stable_time_step();
  for (int k = 0; k < 20000 && ps.time() < 2e-4; ++k) ps.step(dt);
  momentum(c.px1, c.py1);
  c.dv = std::max(std::fabs(ps.vx[0] - 1.0), std::fabs(ps.vx[1] + 0.5));
  return c;
}

}  // namespace

TEST(SizeDistribution, ContactsBetweenClassesConserveMomentum) {
  // 50 um and 100 um particles, the parcels holding the same solid (n_a = 8 n_b), and an
  // arbitrary pair of counts: the pair's forces are equal and opposite on the parcels.
  for (const auto& [n_a, n_b] : {std::pair{8000.0, 1000.0}, std::pair{2500.0, 900.0}}) {
    const Collision c = collide(n_a, 50e-6, n_b, 100e-6);
    EXPECT_GT(c.dv, 0.3);  // they collided
    const double scale = std::hypot(c.px0, c.py0);
    EXPECT_NEAR(c.px1, c.px0, 1e-13 * scale) << n_a << " " << n_b;
    EXPECT_NEAR(c.py1, c.py0, 1e-13 * scale) << n_a << " " << n_b;
  }
}

TEST(SizeDistribution, ContactsOfEqualCountsKeepThePerParticleLaw) {
  // Equal n_real: each parcel moves like one real particle (unchanged law), and momentum holds.
  const Collision c = collide(1000.0, 100e-6, 1000.0, 100e-6);
  EXPECT_GT(c.dv, 0.3);
  EXPECT_NEAR(c.px1, c.px0, 1e-13 * std::hypot(c.px0, c.py0));
}
