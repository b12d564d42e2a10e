// Layer generator and coarse graining (docs/dem.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"

using namespace dustlift;

namespace {

/// Smallest centre distance over all pairs closer than `cell`, by bucketing into cells.
double min_distance(const std::vector<double>& x, const std::vector<double>& y, double cell) {
  const double x0 = *std::min_element(x.begin(), x.end()), y0 = *std::min_element(y.begin(), y.end());
  const double x1 = *std::max_element(x.begin(), x.end()), y1 = *std::max_element(y.begin(), y.end());
  const int nx = static_cast<int>((x1 - x0) / cell) + 1, ny = static_cast<int>((y1 - y0) / cell) + 1;
  std::vector<std::vector<std::size_t>> bucket(static_cast<std::size_t>(nx) * ny);
  auto cx = [&](std::size_t i) { return static_cast<int>((x[i] - x0) / cell); };
  auto cy = [&](std::size_t i) { return static_cast<int>((y[i] - y0) / cell); };
  for (std::size_t i = 0; i < x.size(); ++i) bucket[static_cast<std::size_t>(cy(i)) * nx + cx(i)].push_back(i);
  double best = 1e300;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int b = std::max(0, cy(i) - 1); b <= std::min(ny - 1, cy(i) + 1); ++b) {
      for (int a = std::max(0, cx(i) - 1); a <= std::min(nx - 1, cx(i) + 1); ++a) {
        for (std::size_t j : bucket[static_cast<std::size_t>(b) * nx + a]) {
          if (j != i) best = std::min(best, std::hypot(x[i] - x[j], y[i] - y[j]));
        }
      }
    }
  }
  return best;
}

}  // namespace

TEST(DemLayer, PaperLayerHasSixtyThousandParcelsWithoutOverlap) {
  LayerConfig paper;  // 400 mm x 2 mm, alpha_p 0.59
  const LayerPositions L = generate_layer(paper, 100e-6);
  const double n = static_cast<double>(L.x.size());
  EXPECT_NEAR(n / 60000.0, 1.0, 0.02);
  EXPECT_EQ(static_cast<std::int64_t>(L.x.size()), L.lattice.n_parcels);
  EXPECT_NEAR(areal_fraction(n, 100e-6, 0.4 * 0.002), 0.59, 1e-4);
  EXPECT_GT(min_distance(L.x, L.y, 150e-6), 100e-6);  // no parcel touches another
  for (std::size_t i = 0; i < L.x.size(); ++i) {
    ASSERT_TRUE(L.x[i] >= 50e-6 && L.x[i] <= 0.4 - 50e-6);
    ASSERT_TRUE(L.y[i] >= -0.002 + 50e-6 && L.y[i] <= -50e-6);
  }
  std::printf("paper layer: %zu parcels, lattice %d x %d, pitch %.2f x %.2f um\n", L.x.size(),
              L.lattice.rows, L.lattice.cols, L.lattice.pitch_x * 1e6, L.lattice.pitch_y * 1e6);
}

TEST(DemLayer, SameSeedSameLayerOtherSeedOtherLayer) {
  LayerConfig c{0.0, 0.02, 0.0, 0.002, 0.5, 42, LayerArrangement::JitteredLattice, false};
  const LayerPositions a = generate_layer(c, 100e-6), b = generate_layer(c, 100e-6);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  c.seed = 43;
  const LayerPositions d = generate_layer(c, 100e-6);
  ASSERT_EQ(a.x.size(), d.x.size());
  EXPECT_NE(a.x, d.x);
}

TEST(DemLayer, ImpossibleFractionIsRejected) {
  LayerConfig c{0.0, 0.02, 0.0, 0.002, 0.85, 1, LayerArrangement::Lattice, false};
  EXPECT_THROW(plan_layer_lattice(c, 100e-6), std::invalid_argument);
}

TEST(DemCoarseGraining, RealParticlesPerMetreFollowFromTheVolumeFraction) {
  // §4: 60,000 parcels in 400 mm x 2 mm at alpha_p 0.59 -> 15,024 real particles per
  // parcel per metre; 3-D fraction equals the 2-D areal fraction at 1.5/d = 15,000 /m.
  EXPECT_NEAR(derived_real_per_parcel(0.59, 0.4 * 0.002, 60000.0, 100e-6), 15024.0, 1.0);
  EXPECT_NEAR(equal_fraction_real_per_parcel(100e-6, 100e-6), 15000.0, 1e-9);
  EXPECT_NEAR(volume_fraction_3d(60000.0, 15024.0, 100e-6, 0.4 * 0.002), 0.59, 1e-4);
  // The paper's 90,000 per metre would put 3.53 m^3 of solid in each m^3 of layer.
  EXPECT_NEAR(volume_fraction_3d(60000.0, 90000.0, 100e-6, 0.4 * 0.002), 3.53, 0.01);
  // n_xy = 2: a parcel of 200 um holds 4x the real particles of a 100 um one.
  EXPECT_NEAR(equal_fraction_real_per_parcel(200e-6, 100e-6) / equal_fraction_real_per_parcel(100e-6, 100e-6), 4.0, 1e-12);
}

TEST(DemCoarseGraining, ParcelMassAndCylinderInertia) {
  DemConfig c;
  c.enabled = true;
  c.layer = LayerConfig{0.0, 0.01, -0.002, 0.0, 0.59, 1, LayerArrangement::JitteredLattice, false};
  c.domain = DemDomain{0.0, 0.01, -0.002, 0.02, true, false, false, false, false};
  c.parcel_diameter = 200e-6;  // n_xy = 2
  const ParcelSystem s = make_layer_system(c);
  ASSERT_GT(s.size(), 0u);
  const double m_real = 980.0 * sphere_volume(100e-6);
  const double n = derived_real_per_parcel(0.59, 0.01 * 0.002, static_cast<double>(s.size()), 100e-6);
  EXPECT_NEAR(s.n_real[0] / n, 1.0, 1e-12);
  EXPECT_NEAR(s.mass[0] / (n * m_real), 1.0, 1e-12);
  // Cylinder of the parcel radius: I = m r^2 / 2, i.e. per real particle (4/5) n_xy^2 times
  // a sphere's... inverse relation of eq. (11): omega_dot_parcel = 4/(5 n_xy) omega_dot_real.
  EXPECT_NEAR(s.inertia[0] / (0.5 * s.mass[0] * 100e-6 * 100e-6), 1.0, 1e-12);
  const double torque = 1e-9, r = 100e-6, F = torque / (0.5 * 100e-6);
  const double omega_dot_parcel = n * F * r / s.inertia[0];                    // lever arm n_xy d/2
  const double omega_dot_real = F * 50e-6 / (0.4 * m_real * 50e-6 * 50e-6);  // sphere, r = d/2
  EXPECT_NEAR(omega_dot_parcel / omega_dot_real, 0.8 / 2.0, 1e-12);
  // The whole layer holds alpha_p of solid in 3-D.
  const double area = 0.01 * 0.002;
  EXPECT_NEAR(volume_fraction_3d(static_cast<double>(s.size()), s.n_real[0], 100e-6, area), 0.59, 1e-12);
}
