// Transport: Gordon fits + Wilke rule against docs/gas-solver.md, Sutherland, the model switch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "solver/gas/thermo.hpp"
#include "solver/gas/transport.hpp"

using namespace dustlift;

namespace {
void expect_rel(double got, double want, double rel) { EXPECT_NEAR(got, want, rel * std::abs(want)); }
}  // namespace

TEST(GordonWilke, SpeciesValuesAt300K) {
  expect_rel(nitrogen_transport(300.0).mu, 1.79059e-5, 2e-5);
  expect_rel(oxygen_transport(300.0).mu, 2.07430e-5, 2e-5);
  expect_rel(nitrogen_transport(300.0).lambda, 2.61505e-2, 2e-5);
  expect_rel(oxygen_transport(300.0).lambda, 2.65964e-2, 2e-5);
}

TEST(GordonWilke, AirValuesAt300And384K) {
  const TransportProperties a300 = air_transport_gordon_wilke(300.0);
  expect_rel(a300.mu, 1.85031e-5, 2e-5);
  expect_rel(a300.lambda, 2.62497e-2, 2e-5);
  const ThermallyPerfectAir air;
  EXPECT_NEAR(a300.mu * air.cp(300.0) / a300.lambda, 0.713, 1e-3);  // Prandtl number
  const TransportProperties a384 = air_transport_gordon_wilke(384.2);
  expect_rel(a384.mu, 2.22948e-5, 2e-5);
  expect_rel(a384.lambda, 3.18296e-2, 2e-5);
}

TEST(GordonWilke, FastAirPathEqualsGenericWilkeRule) {
  for (double T : {200.0, 300.0, 384.2, 999.0, 1000.0, 2500.0}) {
    const TransportProperties fast = air_transport_gordon_wilke(T);
    const TransportProperties generic =
        wilke_binary_mixture(oxygen_transport(T), nasa7::kMoleFractionO2, nasa7::kMolarMassO2, nitrogen_transport(T),
                             nasa7::kMoleFractionN2, nasa7::kMolarMassN2);
    expect_rel(fast.mu, generic.mu, 1e-13);
    expect_rel(fast.lambda, generic.lambda, 1e-13);
  }
}

TEST(GordonWilke, TableMatchesTheFits) {
  const GordonWilkeAirTable table;
  auto worst_above = [&](double t_low) {
    double worst = 0.0;
    for (double T = t_low; T < 6500.0; T += 0.37) {
      const TransportProperties a = table(T), b = air_transport_gordon_wilke(T);
      worst = std::max({worst, std::abs(a.mu / b.mu - 1), std::abs(a.lambda / b.lambda - 1)});
    }
    return worst;
  };
  EXPECT_LT(worst_above(200.0), 3e-6);  // the fits' range (measured 2.2e-6 at 201 K)
  EXPECT_LT(worst_above(100.0), 2e-5);  // strong curvature of exp(C/T^2) below it
  EXPECT_EQ(table(10.0).mu, air_transport_gordon_wilke(10.0).mu);  // outside: the fits themselves
}

TEST(GordonWilke, WilkeRuleOfIdenticalSpeciesIsIdentity) {
  const TransportProperties s{2e-5, 3e-2};
  const TransportProperties m = wilke_binary_mixture(s, 0.3, 0.028, s, 0.7, 0.028);
  expect_rel(m.mu, s.mu, 1e-14);
  expect_rel(m.lambda, s.lambda, 1e-14);
}

TEST(Sutherland, ReferenceAndTableValues) {
  const TransportConfig c;
  expect_rel(sutherland_viscosity(273.15, c), 1.716e-5, 1e-14);
  expect_rel(sutherland_viscosity(300.0, c), 1.8459e-5, 2e-4);  // standard air table value
}

TEST(TransportModelSwitch, ConstantAndInviscid) {
  TransportConfig c;
  c.model = TransportModel::Constant;
  c.viscosity = 1e-3;
  c.prandtl = 0.5;
  const TransportProperties t = transport_properties(c, 400.0, 1000.0);
  EXPECT_DOUBLE_EQ(t.mu, 1e-3);
  EXPECT_DOUBLE_EQ(t.lambda, 1e-3 * 1000.0 / 0.5);
  c.model = TransportModel::Inviscid;
  EXPECT_EQ(transport_properties(c, 400.0, 1000.0).mu, 0.0);
}
