// Rankine-Hugoniot jumps against docs/gas-solver.md (Ms = 1.44 into air, 101 kPa, 300 K),
// and the shock-frame conservation laws of the numeric thermally perfect solve.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "solver/gas/shock_relations.hpp"
#include "solver/gas/thermo.hpp"

using namespace dustlift;

namespace {
PrimitiveState air_at_rest(double p, double T, double R) { return {p / (R * T), 0.0, 0.0, p}; }
void expect_rel(double got, double want, double rel) { EXPECT_NEAR(got, want, rel * std::abs(want)); }
}  // namespace

TEST(NormalShock, CaloricallyPerfectMatchesTable) {
  ThermoConfig t;
  t.model = ThermoModel::CaloricallyPerfect;
  t.gamma = 1.4;
  t.gas_constant = 288.19;
  const PrimitiveState pre = air_at_rest(101000.0, 300.0, t.gas_constant);
  const ShockJump j = normal_shock(pre, 1.44, t, 'x');
  expect_rel(pre.rho, 1.16821, 5e-6);
  expect_rel(j.shock_speed, 500.987, 2e-6);
  expect_rel(j.post.p, 227506.0, 5e-6);
  expect_rel(j.post.rho, 2.05474, 5e-6);
  expect_rel(j.post_temperature, 384.199, 3e-6);
  expect_rel(j.post.u, 216.154, 5e-6);
  EXPECT_EQ(j.post.v, 0.0);
}

TEST(NormalShock, ThermallyPerfectMatchesTable) {
  ThermoConfig t;  // default: thermally perfect air, R = 288.190
  const PrimitiveState pre = air_at_rest(101000.0, 300.0, t.gas_constant);
  const ShockJump j = normal_shock(pre, 1.44, t, 'x');
  expect_rel(j.shock_speed, 500.712, 2e-6);
  expect_rel(j.post.p, 227695.0, 5e-6);
  expect_rel(j.post.rho, 2.05879, 5e-6);
  expect_rel(j.post_temperature, 383.763, 3e-6);
  expect_rel(j.post.u, 216.595, 5e-6);
}

TEST(NormalShock, ThermallyPerfectConservesMassMomentumEnthalpy) {
  ThermoConfig t;
  const ThermallyPerfectAir air(t.gas_constant);
  for (double mach : {1.1, 1.44, 2.5, 5.0}) {
    const PrimitiveState pre{1.2, 30.0, 0.0, 1e5};  // moving pre-shock gas too
    const ShockJump j = normal_shock(pre, mach, t, 'x');
    const double w1 = j.shock_speed - pre.u, w2 = j.shock_speed - j.post.u;
    const double T1 = pre.p / (pre.rho * t.gas_constant);
    expect_rel(std::sqrt(air.sound_speed_squared(T1)) * mach, w1, 1e-14);
    expect_rel(pre.rho * w1, j.post.rho * w2, 1e-12);
    expect_rel(pre.p + pre.rho * w1 * w1, j.post.p + j.post.rho * w2 * w2, 1e-12);
    expect_rel(air.enthalpy(T1) + 0.5 * w1 * w1, air.enthalpy(j.post_temperature) + 0.5 * w2 * w2, 1e-11);
    EXPECT_GT(j.post.p, pre.p);
  }
}

TEST(NormalShock, AlongYAndInvalidInput) {
  ThermoConfig t;
  const PrimitiveState pre = air_at_rest(101000.0, 300.0, t.gas_constant);
  const ShockJump x = normal_shock(pre, 1.44, t, 'x');
  const ShockJump y = normal_shock(pre, 1.44, t, 'y');
  EXPECT_EQ(x.post.u, y.post.v);
  EXPECT_EQ(y.post.u, 0.0);
  EXPECT_THROW(normal_shock(pre, 0.9, t, 'x'), std::invalid_argument);
}
