// Thermodynamics: NASA-7 air against the reference values of docs/gas-solver.md,
// range continuity, and the safeguarded Newton inversion e -> T.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "solver/gas/thermo.hpp"

using namespace dustlift;

TEST(ThermallyPerfectAir, CpAndGammaMatchReferenceValues) {
  const ThermallyPerfectAir air(288.190);
  EXPECT_NEAR(air.cp(300.0), 1011.44, 0.01);
  EXPECT_NEAR(air.gamma(300.0), 1.39847, 1e-5);
  EXPECT_NEAR(air.cp(500.0), 1036.71, 0.01);
  EXPECT_NEAR(air.gamma(500.0), 1.38501, 1e-5);
  EXPECT_NEAR(air.cp(1000.0), 1148.85, 0.01);
  EXPECT_NEAR(air.gamma(1000.0), 1.33485, 1e-5);
}

TEST(ThermallyPerfectAir, PolynomialRangesJoinAt1000K) {
  for (const auto& [lo, hi] : {std::pair{nasa7::kN2Low, nasa7::kN2High}, std::pair{nasa7::kO2Low, nasa7::kO2High}}) {
    const double cl = nasa7::cp_over_r(lo, 1000.0), ch = nasa7::cp_over_r(hi, 1000.0);
    EXPECT_LT(std::abs(cl - ch) / cl, 3e-8);
  }
  const ThermallyPerfectAir air;
  EXPECT_LT(std::abs(air.cp(1000.0 - 1e-9) - air.cp(1000.0)) / air.cp(1000.0), 3e-8);
  // Enthalpy continuous to the precision of the tabulated a6 (about 1e-6 relative).
  EXPECT_LT(std::abs(air.enthalpy(1000.0 - 1e-9) - air.enthalpy(1000.0)) / air.enthalpy(1000.0), 1e-5);
}

TEST(ThermallyPerfectAir, AbsoluteEnthalpyOfElementsVanishesAt298K) {
  const ThermallyPerfectAir air;
  // Reference elements: h(298.15 K) = 0; compare with cp*T ~ 3e5 J/kg.
  EXPECT_LT(std::abs(air.absolute_enthalpy(298.15)), 50.0);
}

TEST(ThermallyPerfectAir, SensibleEnergyIsCpIntegral) {
  const ThermallyPerfectAir air;
  // e(T2) - e(T1) = int cv dT, by Simpson's rule on [300, 400] K.
  const int n = 200;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double T = 300.0 + 100.0 * k / n;
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * air.cv(T);
  }
  const double integral = sum * (100.0 / n) / 3.0;
  EXPECT_NEAR(air.internal_energy(400.0) - air.internal_energy(300.0), integral, 1e-6 * integral);
  EXPECT_GT(air.internal_energy(1.0), 0.0);
}

TEST(ThermallyPerfectAir, NewtonInversionRecoversTemperature) {
  const ThermallyPerfectAir air;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double T : {50.0, 250.0, 300.0, 384.2, 999.999, 1000.0, 1000.001, 2500.0, 5900.0}) {
    for (double guess : {T, 300.0, 20.0, 6000.0, 1e9, nan}) {
      const double got = air.temperature(air.internal_energy(T), guess);
      EXPECT_NEAR(got, T, 1e-9 * T) << "T=" << T << " guess=" << guess;
    }
  }
  EXPECT_TRUE(std::isnan(air.temperature(nan, 300.0)));
  EXPECT_LT(air.temperature(-1000.0, 300.0), 0.0);  // unphysical energy -> T < 0, caught as p < 0
}

TEST(ThermallyPerfectAir, BatchTemperaturesAgreeWithScalarSolve) {
  const ThermallyPerfectAir air;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> e, guess;
  for (double T : {30.0, 250.0, 300.0, 301.0, 383.76, 999.99, 1000.01, 1500.0, 5999.0, 7000.0}) {
    for (double g : {T, T * 1.001, T * 0.7, 300.0, nan, -5.0, 1e7}) {
      e.push_back(air.internal_energy(T));
      guess.push_back(g);
    }
  }
  e.push_back(-10.0);  // unphysical: T < 0 as in the scalar solve
  guess.push_back(300.0);
  e.push_back(nan);
  guess.push_back(300.0);
  std::vector<double> T(e.size());
  air.temperatures(e.data(), guess.data(), T.data(), static_cast<int>(e.size()));
  for (std::size_t k = 0; k + 1 < e.size(); ++k) {
    const double scalar = air.temperature(e[k], guess[k]);
    EXPECT_NEAR(T[k], scalar, 1e-11 * std::abs(scalar)) << "e=" << e[k] << " guess=" << guess[k];
  }
  EXPECT_LT(T[e.size() - 2], 0.0);
  EXPECT_TRUE(std::isnan(T.back()));
}

TEST(CaloricallyPerfectGas, GammaLawRelations) {
  const CaloricallyPerfectGas g(1.4, 287.0);
  EXPECT_DOUBLE_EQ(g.cp(123.0), 1.4 * 287.0 / 0.4);
  EXPECT_DOUBLE_EQ(g.cv(123.0) * 1.4, g.cp(123.0));
  EXPECT_DOUBLE_EQ(g.temperature(g.internal_energy(345.0), 0.0), 345.0);
  EXPECT_NEAR(std::sqrt(g.sound_speed_squared(300.0)), 347.1887, 1e-4);
}
