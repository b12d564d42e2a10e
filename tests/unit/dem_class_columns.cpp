// Parcels of a size per class (particles.parcel_ratio, solver/dem/class_columns.hpp): the plan
// puts each class's mass share and the layer's 3-D fraction in columns of one class, the layer
// starts at rest without overlaps, and a box of two classes of different parcel ratios keeps
// its momentum and mass to round-off through contacts, restitution and cohesion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <vector>

#include "solver/dem/class_columns.hpp"
#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/contact.hpp"

using namespace dustlift;

namespace {

/// A 20 mm x 0.5 mm columnar layer at 0.5 of 20 um (ratio 4) and 60 um (ratio 2) particles,
/// 40 % and 60 % of the mass.
DemConfig two_classes() {
  DemConfig c;
  c.enabled = true;
  c.layer.touching_columns = false;  // the spread columns; touching ones in their own tests
  c.density = 1500.0;
  c.size_classes = {{20e-6, 0.4, 80e-6}, {60e-6, 0.6, 120e-6}};
  c.particle_diameter = 60e-6;
  c.parcel_diameter = 120e-6;
  c.layer.x_min = 0.0;
  c.layer.x_max = 0.02;
  c.layer.y_min = -0.0005;
  c.layer.y_max = 0.0;
  c.layer.volume_fraction = 0.5;
  c.layer.arrangement = LayerArrangement::Columnar;
  c.layer.seed = 3;
  c.contact = ContactParams{7.5e3, 15.0, 0.0, 0.5};
  c.contact.restitution = 0.9;
  c.wall_contact = c.contact;
  c.domain = DemDomain{0.0, 0.02, -0.0005, 0.005, true, false, false, false, false};
  return c;
}

double layer_mass(const DemConfig& c) {
  const LayerConfig& L = c.layer;
  return c.density * L.volume_fraction * (L.x_max - L.x_min) * (L.y_max - L.y_min);
}

}  // namespace

TEST(ClassColumns, EachClassHoldsItsMassShareInColumnsOfItsOwnParcels) {
  const DemConfig cfg = two_classes();
  const ClassColumns plan = plan_class_columns(cfg);
  const ParcelSystem s = make_layer_system(cfg);
  ASSERT_EQ(static_cast<std::int64_t>(s.size()), plan.parcels);
  double mass[2] = {0.0, 0.0}, solid = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto k = static_cast<std::size_t>(s.size_class[i]);
    mass[k] += s.mass[i];
    solid += s.n_real[i] * sphere_volume(s.real_diameter[i]);
    EXPECT_EQ(s.diameter[i], cfg.size_classes[k].parcel_diameter);
    EXPECT_EQ(s.real_diameter[i], cfg.size_classes[k].diameter);
  }
  const LayerConfig& L = cfg.layer;
  const double area = (L.x_max - L.x_min) * (L.y_max - L.y_min);
  // The 3-D solid fraction is the layer's to round-off.
  EXPECT_NEAR(solid / area / L.volume_fraction, 1.0, 1e-12);
  // Each class's share of the mass within one column's share of the width.
  for (std::size_t k = 0; k < 2; ++k) {
    const double share = mass[k] / layer_mass(cfg);
    EXPECT_NEAR(share, cfg.size_classes[k].mass_fraction, plan.width[k] / (L.x_max - L.x_min)) << k;
    std::printf("class %zu: %d rows x %lld columns of %.2f um, %lld parcels, mass share %.4f\n", k,
                plan.rows[k], static_cast<long long>(plan.columns[k]), plan.width[k] * 1e6,
                static_cast<long long>(plan.rows[k] * plan.columns[k]), share);
  }
  // Every column's top parcel touches the layer top; the columns interleave.
  std::set<double> tops;
  double highest = -1.0;
  for (std::size_t i = 0; i < s.size(); ++i) highest = std::max(highest, s.y[i] + s.radius[i]);
  EXPECT_NEAR(highest, L.y_max, 1e-15);
  int changes = 0;
  for (std::size_t c = 1; c < plan.order.size(); ++c) changes += plan.order[c] != plan.order[c - 1];
  EXPECT_GT(changes, static_cast<int>(plan.order.size()) / 4);
}

TEST(ClassColumns, TheLayerStartsAtRestWithoutOverlaps) {
  DemConfig cfg = two_classes();
  cfg.cohesion.hamaker = 1e-19;  // would pull touching parcels together
  ParcelSystem s = make_layer_system(cfg);
  s.step(s.stable_time_step());
  EXPECT_EQ(s.contact_pair_count(), 0u);
  EXPECT_EQ(s.kinetic_energy(), 0.0);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_GE(s.y[i] - cfg.layer.y_min, s.radius[i]);
}

TEST(ClassColumns, TooDenseOrTooFewColumnsAreRefused) {
  DemConfig dense = two_classes();
  dense.layer.touching_columns = false;  // spread columns hold the fraction in their discs
  dense.layer.volume_fraction = 0.8;
  try {
    plan_class_columns(dense);
    FAIL() << "0.8 packed";
  } catch (const ClassColumnsError& e) {
    EXPECT_TRUE(e.too_dense) << e.what();
  }
  DemConfig narrow = two_classes();
  narrow.layer.x_max = 0.0001;
  try {
    plan_class_columns(narrow);
    FAIL() << "a 0.1 mm layer gave every class a column";
  } catch (const ClassColumnsError& e) {
    EXPECT_FALSE(e.too_dense) << e.what();
  }
}

TEST(ClassColumns, BoxOfTwoParcelRatiosConservesMomentumAndMass) {
  // The layer thrown about in a box without walls (periodic along x): contacts between the
  // classes (the pair rule), restitution per pair and cohesion; the parcels' total momentum
  // must stay what it was to round-off.
  DemConfig cfg = two_classes();
  cfg.layer.x_max = cfg.domain.x_max = 0.005;
  cfg.domain.wall_bottom = false;
  cfg.domain.periodic_x = true;
  cfg.cohesion.hamaker = 1e-20;
  cfg.cohesion.cutoff = 1e-6;
  ParcelSystem s = make_layer_system(cfg);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double a = std::sin(12.9898 * static_cast<double>(k) + 1.0),
                 b = std::cos(78.233 * static_cast<double>(k));
    s.vx[k] = 20.0 * a;
    s.vy[k] = 20.0 * b;
    s.omega[k] = 1e4 * a * b;
  }
  // Summed in id order (the parcels are re-sorted by cell as they move).
  const auto totals = [&](double& px, double& py, double& scale, double& m) {
    px = py = scale = m = 0.0;
    std::vector<std::size_t> by_id(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) by_id[static_cast<std::size_t>(s.id[i])] = i;
    for (const std::size_t i : by_id) {
      px += s.mass[i] * s.vx[i];
      py += s.mass[i] * s.vy[i];
      scale += s.mass[i] * std::hypot(s.vx[i], s.vy[i]);
      m += s.mass[i];
    }
  };
  double px0, py0, scale, m0;
  totals(px0, py0, scale, m0);
  const double dt = s.stable_time_step();
  std::size_t contacts = 0, mixed = 0;
  for (int k = 0; k < 20000; ++k) {
    s.step(dt);
    if (k % 500 == 0) {
      contacts += s.contact_pair_count();
      for (std::size_t i = 0; i + 1 < s.nbr_offset.size(); ++i)
        for (std::int32_t q = s.nbr_offset[i]; q < s.nbr_offset[i + 1]; ++q) {
          const auto j = static_cast<std::size_t>(s.nbr_index[static_cast<std::size_t>(q)]);
          const double dx = s.x[j] - s.x[i], dy = s.y[j] - s.y[i];
          if (s.size_class[i] != s.size_class[j] && std::hypot(dx, dy) < s.radius[i] + s.radius[j])
            ++mixed;
        }
    }
  }
  double px, py, scale1, m;
  totals(px, py, scale1, m);
  std::printf(
      "%zu parcels, %zu contacts sampled (%zu between classes): momentum change "
      "(%.3g, %.3g) of %.3g, mass %.17g -> %.17g\n",
      s.size(), contacts, mixed / 2, px - px0, py - py0, scale, m0, m);
  EXPECT_GT(mixed, 10u);
  EXPECT_NEAR((px - px0) / scale, 0.0, 1e-13);
  EXPECT_NEAR((py - py0) / scale, 0.0, 1e-13);
  EXPECT_EQ(m, m0);
  EXPECT_NEAR(m / layer_mass(cfg), 1.0, 0.02);
}

TEST(ClassColumns, TouchingColumnsStandSideBySideAndHoldTheFractionInTheirRealParticles) {
  // Columns one parcel wide, side by side: the discs cover pi/4 rows D / depth of the layer
  // (0.74 for 80 um parcels in 6 rows of 0.5 mm) while the real particles hold volume_fraction.
  DemConfig cfg = two_classes();
  cfg.layer.touching_columns = true;
  const ClassColumns plan = plan_class_columns(cfg);
  const LayerConfig& L = cfg.layer;
  const double width = L.x_max - L.x_min, depth = L.y_max - L.y_min;
  EXPECT_GE(plan.stretch, 1.0);
  EXPECT_LT(plan.stretch, 1.0 + 2 * 120e-6 / width);  // within one column's share
  double filled = 0.0;
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_DOUBLE_EQ(plan.width[k], cfg.size_classes[k].parcel_diameter * plan.stretch) << k;
    filled += static_cast<double>(plan.columns[k]) * plan.width[k];
  }
  EXPECT_NEAR(filled, width, 1e-15);
  ParcelSystem s = make_layer_system(cfg);
  ASSERT_EQ(static_cast<std::int64_t>(s.size()), plan.parcels);
  double solid = 0.0, discs = 0.0, mass[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < s.size(); ++i) {
    solid += s.n_real[i] * sphere_volume(s.real_diameter[i]);
    discs += disc_area(s.diameter[i]);
    mass[static_cast<std::size_t>(s.size_class[i])] += s.mass[i];
  }
  EXPECT_NEAR(solid / (width * depth) / L.volume_fraction, 1.0, 1e-12);
  const double covered = discs / (width * depth);
  std::printf("touching: %lld + %lld columns, stretch %.6f, discs cover %.4f of the layer\n",
              static_cast<long long>(plan.columns[0]), static_cast<long long>(plan.columns[1]),
              plan.stretch, covered);
  EXPECT_GT(covered, 0.7);  // spread columns at 0.5 would cover 0.5
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_NEAR(mass[k] / layer_mass(cfg), cfg.size_classes[k].mass_fraction, plan.width[k] / width)
        << k;
  // Touching, not overlapping: at rest, no contact counted, neighbours within round-off.
  s.step(s.stable_time_step());
  EXPECT_EQ(s.contact_pair_count(), 0u);
  EXPECT_EQ(s.kinetic_energy(), 0.0);
  double widest_gap = 0.0;
  std::vector<std::size_t> tops;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (std::abs(s.y[i] + s.radius[i] - L.y_max) < 1e-12) tops.push_back(i);
  std::sort(tops.begin(), tops.end(),
            [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
  for (std::size_t q = 1; q < tops.size(); ++q) {
    const std::size_t a = tops[q - 1], b = tops[q];
    widest_gap = std::max(widest_gap, s.x[b] - s.x[a] - s.radius[a] - s.radius[b]);
  }
  EXPECT_LT(widest_gap, (plan.stretch - 1.0) * 120e-6 + 1e-12);
}

TEST(ClassColumns, TouchingColumnsThatWouldNotFitLoseAColumnOfTheClassMostOverItsShare) {
  // 1.000 mm of 80 um and 120 um columns at 40/60 %: round(5.0) + round(5.0) columns are
  // 0.4 + 0.6 mm; widening the layer by less than a column keeps them, narrowing it by a hair
  // drops one column of one class, never squeezes the columns.
  DemConfig cfg = two_classes();
  cfg.layer.touching_columns = true;
  cfg.layer.x_max = 0.001 - 1e-9;
  const ClassColumns plan = plan_class_columns(cfg);
  double filled = 0.0;
  for (std::size_t k = 0; k < 2; ++k)
    filled += static_cast<double>(plan.columns[k]) * cfg.size_classes[k].parcel_diameter;
  EXPECT_LE(filled, cfg.layer.x_max);
  EXPECT_EQ(plan.columns[0] + plan.columns[1], 9);
  EXPECT_GE(plan.stretch, 1.0);
}
