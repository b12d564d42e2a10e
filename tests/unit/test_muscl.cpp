// MUSCL reconstruction: exactness on linear data, kappa = 1/3 exactness for quadratic cell
// averages, limiting at extrema, boundedness (TVD) of the minmod-b limiter, first order.
#include <gtest/gtest.h>

#include <random>

#include "solver/gas/muscl.hpp"

using namespace dustlift;

namespace {
MusclSettings settings(double kappa, Limiter lim, double b) {
  MusclSettings m;
  m.order = Reconstruction::Muscl3;
  m.kappa = kappa;
  m.limiter = lim;
  m.b = b;
  return m;
}
}  // namespace

TEST(Muscl, LinearDataReproducedByEverySetting) {
  for (double kappa : {-1.0, 0.0, 1.0 / 3.0}) {
    for (Limiter lim : {Limiter::Minmod, Limiter::VanAlbada}) {
      const FacePair f = muscl_face(1.0, 3.0, 5.0, 7.0, settings(kappa, lim, 2.0));
      EXPECT_NEAR(f.left, 4.0, 1e-12);
      EXPECT_NEAR(f.right, 4.0, 1e-12);
    }
  }
}

TEST(Muscl, KappaOneThirdExactForQuadraticCellAverages) {
  // Cell averages of x^2 over [i-1/2, i+1/2] are i^2 + 1/12; the face value at i+1/2 is (i+1/2)^2.
  auto avg = [](double i) { return i * i + 1.0 / 12.0; };
  const MusclSettings m = settings(1.0 / 3.0, Limiter::Minmod, 4.0);
  for (int i = 3; i < 8; ++i) {
    const FacePair f = muscl_face(avg(i - 1), avg(i), avg(i + 1), avg(i + 2), m);
    EXPECT_NEAR(f.left, (i + 0.5) * (i + 0.5), 1e-12);
    EXPECT_NEAR(f.right, (i + 0.5) * (i + 0.5), 1e-12);
  }
}

TEST(Muscl, ExtremumIsFlattenedByMinmod) {
  const FacePair f = muscl_face(1.0, 3.0, 2.0, 0.0, settings(1.0 / 3.0, Limiter::Minmod, 2.0));
  EXPECT_EQ(f.left, 3.0);   // cell 0 is a maximum: zero slope
  EXPECT_LE(f.right, 3.0);  // stays within the neighbours
  EXPECT_GE(f.right, 2.0);
  const FacePair va = muscl_face(1.0, 3.0, 2.0, 0.0, settings(1.0 / 3.0, Limiter::VanAlbada, 2.0));
  EXPECT_EQ(va.left, 3.0);
}

TEST(Muscl, MinmodFaceValuesStayBetweenNeighbours) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (double kappa : {-1.0, 0.0, 1.0 / 3.0}) {
    const double b_max = (3.0 - kappa) / (1.0 - kappa);
    for (Limiter lim : {Limiter::Minmod, Limiter::VanAlbada}) {
      for (int n = 0; n < 2000; ++n) {
        const double q[4] = {d(rng), d(rng), d(rng), d(rng)};
        const FacePair f = muscl_face(q[0], q[1], q[2], q[3], settings(kappa, lim, b_max));
        const double lo = std::min(q[1], q[2]) - 1e-14, hi = std::max(q[1], q[2]) + 1e-14;
        EXPECT_TRUE(f.left >= lo && f.left <= hi) << kappa << " " << q[0] << " " << q[1] << " " << q[2];
        EXPECT_TRUE(f.right >= lo && f.right <= hi) << kappa << " " << q[1] << " " << q[2] << " " << q[3];
      }
    }
  }
}

TEST(Muscl, FirstOrderReturnsCellValues) {
  MusclSettings m;
  m.order = Reconstruction::FirstOrder;
  const FacePair f = muscl_face(1.0, 2.0, 4.0, 8.0, m);
  EXPECT_EQ(f.left, 2.0);
  EXPECT_EQ(f.right, 4.0);
}

TEST(Muscl, SettingsFromScheme) {
  SchemeConfig s;
  s.reconstruction = Reconstruction::Muscl2;
  EXPECT_EQ(muscl_settings(s).kappa, -1.0);
  s.reconstruction = Reconstruction::Muscl3;
  EXPECT_NEAR(muscl_settings(s).kappa, 1.0 / 3.0, 1e-16);
  s.minmod_b = 4.0;
  EXPECT_DOUBLE_EQ(muscl_settings(s).b, 4.0);
  s.reconstruction = Reconstruction::Muscl2;
  EXPECT_DOUBLE_EQ(muscl_settings(s).b, 2.0);  // clamped to the kappa = -1 bound
}
