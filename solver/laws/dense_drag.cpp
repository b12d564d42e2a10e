#include "solver/laws/dense_drag.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dustlift::aero {
namespace {

/// Free-molecular drag coefficient of a sphere at the same temperature as the gas, times M^4
/// (finite as M -> 0; Loth et al. 2021), s = M sqrt(gamma / 2).
double m4_cd_free_molecular(double m, double gamma) {
  const double g = std::sqrt(0.5 * gamma), s = m * g, s2 = s * s;
  const double sqrt_pi = std::sqrt(std::numbers::pi);
  return (1.0 + 2.0 * s2) * std::exp(-s2) * m / (g * g * g * sqrt_pi) +
         (4.0 * s2 * s2 + 4.0 * s2 - 1.0) * std::erf(s) / (2.0 * g * g * g * g) +
         2.0 * sqrt_pi * m * m * m / (3.0 * g);
}

/// Loth's J_M (the free-molecular limit's Reynolds-number blend), times M^4.
double m4_jm(double m) {
  const double m2 = m * m;
  if (m <= 1.0) return 2.26 * m2 * m2 - 0.1 * m2 * m + 0.14 * m;
  return 1.6 * m2 * m2 + 0.25 * m2 * m + 0.11 * m2 + 0.44 * m;
}

}  // namespace

double tenneti_drag_factor(double re, double phi) {
  const double ag = 1.0 - phi, re_m = ag * re;
  const double f_isol = 1.0 + 0.15 * std::pow(re_m, 0.687);
  const double f_phi = 5.81 * phi / (ag * ag * ag) + 0.48 * std::cbrt(phi) / (ag * ag * ag * ag);
  const double phi3 = phi * phi * phi;
  const double f_phi_re = phi3 * re_m * (0.95 + 0.61 * phi3 / (ag * ag));
  return ag * ag * (f_isol / (ag * ag * ag) + f_phi + f_phi_re);
}

double knudsen_number(double rho, double mu, double c, double d, double gamma) {
  return std::sqrt(0.5 * std::numbers::pi * gamma) * mu / (rho * c * d);
}

double re_cd_loth(double re, double m, double kn, double gamma) {
  const double continuum = 1.0 + 0.15 * std::pow(re, 0.687);  // Re C_D / 24 of Schiller-Naumann
  if (re <= 45.0) {
    const double f_kn = 1.0 / (1.0 + kn * (2.514 + 0.8 * std::exp(-0.55 / kn)));
    const double rarefied = continuum * f_kn;
    const double m4 = m * m * m * m;
    // Below M = 1e-4 the free-molecular share M^4 / (1 + M^4) is under 1e-16.
    if (m < 1e-4) return rarefied;
    const double m4_fm = m4_cd_free_molecular(m, gamma);
    const double m4_cd2 = m4_fm / (1.0 + (m4_fm / m4_jm(m) - 1.0) * std::sqrt(re / 45.0));
    return (rarefied + re / 24.0 * m4_cd2) / (1.0 + m4);
  }
  const double c_m =
      m < 1.5 ? 1.65 + 0.65 * std::tanh(4.0 * m - 3.4) : 2.18 - 0.13 * std::tanh(0.9 * m - 2.7);
  const double g_m =
      m < 0.8 ? 166.0 * m * m * m + 3.29 * m * m - 10.9 * m + 20.0 : 5.0 + 40.0 / (m * m * m);
  const double h_m = m < 1.0 ? 0.0239 * m * m * m + 0.212 * m * m - 0.074 * m + 1.0
                             : 0.93 + 1.0 / (3.5 + m * m * m * m * m);
  return continuum * h_m +
         re / 24.0 * 0.42 * c_m / (1.0 + 42500.0 / std::pow(re, 1.16 * c_m) + g_m / std::sqrt(re));
}

double osnes_drag_factor(double re, double m, double kn, double gamma, double phi) {
  const double ag = 1.0 - phi;
  const double b1 = 5.81 * phi / (ag * ag) + 0.48 * std::cbrt(phi) / (ag * ag * ag);
  const double phi3 = phi * phi * phi;
  const double b2 = ag * ag * phi3 * re * (0.95 + 0.61 * phi3 / (ag * ag));
  const double b3 = std::min(std::sqrt(20.0 * m), 1.0) *
                    (5.65 * phi - 22.0 * phi * phi + 23.4 * phi3) *
                    (1.0 + std::tanh((m - (0.65 - 0.24 * phi)) / 0.35));
  // Re C_D / 24 with each term of C_D times Re / 24 (finite as Re -> 0).
  return re_cd_loth(re, m, kn, gamma) / ag + re / 24.0 * b3 + ag * (b1 + b2);
}

double ergun_drag_factor(double re, double phi) {
  return 150.0 / 18.0 * phi / (1.0 - phi) + 1.75 / 18.0 * re;
}

}  // namespace dustlift::aero
