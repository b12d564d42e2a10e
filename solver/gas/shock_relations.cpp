#include "solver/gas/shock_relations.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "solver/gas/thermo.hpp"

namespace dustlift {
namespace {

/// Density ratio rho2/rho1 of a perfect-gas shock.
double perfect_gas_density_ratio(double gamma, double mach) {
  return (gamma + 1.0) * mach * mach / ((gamma - 1.0) * mach * mach + 2.0);
}

/// Shock-frame solve with h(T): unknown density ratio r = rho2/rho1. For a given r, mass gives
/// w2 = w1/r, momentum p2 = p1 + m (w1 - w2), EOS T2 = p2/(rho2 R); the energy residual
/// h(T2) + w2^2/2 - h1 - w1^2/2 is driven to zero by the secant method started from the
/// perfect-gas ratio with gamma(T1) (well away from the trivial root r = 1).
double thermally_perfect_density_ratio(const ThermallyPerfectAir& air, double rho1, double p1, double T1,
                                       double w1, double mach) {
  const double R = air.gas_constant();
  const double m = rho1 * w1;
  const double h0 = air.enthalpy(T1) + 0.5 * w1 * w1;
  auto residual = [&](double r) {
    const double w2 = w1 / r;
    const double p2 = p1 + m * (w1 - w2);
    const double T2 = p2 / (r * rho1 * R);
    return air.enthalpy(T2) + 0.5 * w2 * w2 - h0;
  };
  double r0 = perfect_gas_density_ratio(air.gamma(T1), mach);
  double r1 = 1.001 * r0;
  double f0 = residual(r0), f1 = residual(r1);
  for (int iter = 0; iter < 100 && std::abs(r1 - r0) > 1e-14 * r1; ++iter) {
    if (f1 == f0) break;
    const double r2 = r1 - f1 * (r1 - r0) / (f1 - f0);
    r0 = r1;
    f0 = f1;
    r1 = r2;
    f1 = residual(r1);
  }
  if (!(r1 > 1.0 + 1e-9) || !(std::abs(f1) <= 1e-9 * h0)) {
    throw std::invalid_argument("normal_shock: Rankine-Hugoniot solve with h(T) did not converge (Mach " +
                                std::to_string(mach) + ")");
  }
  return r1;
}

}  // namespace

ShockJump normal_shock(const PrimitiveState& pre, double mach, const ThermoConfig& thermo, char axis) {
  if (!(mach > 1.0)) throw std::invalid_argument("normal_shock: Mach number must exceed 1");
  if (axis != 'x' && axis != 'y') throw std::invalid_argument("normal_shock: axis must be 'x' or 'y'");
  const double R = thermo.gas_constant;
  const double T1 = temperature_of(pre, R);
  const double un1 = axis == 'x' ? pre.u : pre.v;

  double c1 = 0.0, r = 0.0, p2 = 0.0;
  if (thermo.model == ThermoModel::CaloricallyPerfect) {
    const double g = thermo.gamma;
    c1 = std::sqrt(g * R * T1);
    r = perfect_gas_density_ratio(g, mach);
    p2 = pre.p * (1.0 + 2.0 * g / (g + 1.0) * (mach * mach - 1.0));
  } else {
    const ThermallyPerfectAir air(R);
    c1 = std::sqrt(air.sound_speed_squared(T1));
    const double w1 = mach * c1;
    r = thermally_perfect_density_ratio(air, pre.rho, pre.p, T1, w1, mach);
    p2 = pre.p + pre.rho * w1 * (w1 - w1 / r);
  }
  const double w1 = mach * c1;           // gas speed into the shock, shock frame
  const double W = un1 + w1;             // lab shock speed
  const double un2 = W - w1 / r;         // lab normal velocity behind
  ShockJump jump;
  jump.post = pre;
  jump.post.T = std::numeric_limits<double>::quiet_NaN();  // the post-shock T follows p = rho R T
  jump.post.rho = pre.rho * r;
  jump.post.p = p2;
  (axis == 'x' ? jump.post.u : jump.post.v) = un2;
  jump.shock_speed = W;
  jump.pre_temperature = T1;
  jump.post_temperature = p2 / (jump.post.rho * R);
  return jump;
}

}  // namespace dustlift
