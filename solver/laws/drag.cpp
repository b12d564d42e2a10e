#include "solver/laws/drag.hpp"

#include <algorithm>
#include <cmath>

#include "solver/laws/dense_drag.hpp"

namespace dustlift::aero {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Re * C_D of the fits 24/Re (1 + a Re^b) + c / (1 + e / Re^f) at Re = re > 0 with
/// l = ln Re: the powers as exp(b l) (pow costs two of each), and one logarithm serves every
/// fit evaluated at the same Re (re_cd_parmar needs two or three).
double re_cd_fit_ln(double re, double l, double a, double b, double c, double e, double f) {
  return 24.0 * (1.0 + a * std::exp(b * l)) + c * re / (1.0 + e * std::exp(-f * l));
}

/// The same fit, finite at Re -> 0.
double re_cd_fit(double re, double a, double b, double c, double e, double f) {
  if (re <= 0.0) return 24.0;
  return re_cd_fit_ln(re, std::log(re), a, b, c, e, f);
}

double re_cd_standard_ln(double re, double l) {
  return re_cd_fit_ln(re, l, 0.15, 0.687, 0.42, 42500.0, 1.16);
}
double re_cd_mcr_ln(double re, double l) {
  return re_cd_fit_ln(re, l, 0.15, 0.684, 0.513, 483.0, 0.669);
}
double re_cd_m1_ln(double re, double l) {
  return re_cd_fit_ln(re, l, 0.118, 0.813, 0.69, 3550.0, 0.793);
}
double re_cd_m175_ln(double re, double l) {
  return re_cd_fit_ln(re, l, 0.107, 0.867, 0.646, 861.0, 0.634);
}

/// Quadratic Lagrange interpolation in l = ln Re through nodes C1..C3 with values f1..f3
/// (Parmar et al. 2010, eq. for zeta).
double lagrange_ln_re(double l, const double (&c)[3], const double (&f)[3]) {
  double z = 0.0;
  for (int i = 0; i < 3; ++i) {
    double w = f[i];
    for (int j = 0; j < 3; ++j) {
      if (j != i) w *= (l - c[j]) / (c[i] - c[j]);
    }
    z += w;
  }
  return z;
}

}  // namespace

double re_cd_standard(double re) {
  return re_cd_fit(re, 0.15, 0.687, 0.42, 42500.0, 1.16);
}

double cd_standard(double re) {
  return re_cd_standard(re) / re;
}

double re_cd_parmar(double m, double re) {
  constexpr double kMcr = 0.6;
  // Every fit is 24 at Re = 0 (and the interpolations between them then too).
  if (re <= 0.0) return 24.0;
  const double l = std::log(re);
  const double l_lagrange = re >= 1e-300 ? l : std::log(1e-300);  // ln Re kept finite
  if (m <= kMcr) {
    const double std_value = re_cd_standard_ln(re, l);
    return std_value + (re_cd_mcr_ln(re, l) - std_value) * m / kMcr;
  }
  if (m <= 1.0) {
    static constexpr double c[3] = {6.48, 9.28, 12.21};
    const double f[3] = {-1.884 + 8.422 * m - 13.70 * m * m + 8.162 * m * m * m,
                         -2.228 + 10.35 * m - 16.96 * m * m + 9.840 * m * m * m,
                         4.362 - 16.91 * m + 19.84 * m * m - 6.296 * m * m * m};
    const double zeta1 = lagrange_ln_re(l_lagrange, c, f);
    const double mcr = re_cd_mcr_ln(re, l);
    return mcr + (re_cd_m1_ln(re, l) - mcr) * zeta1;
  }
  const double ms = std::min(m, 1.75);  // the fits end at M = 1.75; hold beyond
  static constexpr double c[3] = {6.48, 8.93, 12.21};
  const double f[3] = {-2.963 + 4.392 * ms - 1.169 * ms * ms - 0.027 * ms * ms * ms -
                           0.233 * std::exp((1.0 - ms) / 0.011),
                       -6.617 + 12.11 * ms - 6.501 * ms * ms + 1.182 * ms * ms * ms -
                           0.174 * std::exp((1.0 - ms) / 0.010),
                       -5.866 + 11.57 * ms - 6.665 * ms * ms + 1.312 * ms * ms * ms -
                           0.350 * std::exp((1.0 - ms) / 0.012)};
  const double zeta2 = lagrange_ln_re(l_lagrange, c, f);
  const double m1 = re_cd_m1_ln(re, l);
  return m1 + (re_cd_m175_ln(re, l) - m1) * zeta2;
}

double cd_parmar(double m, double re) {
  return re_cd_parmar(m, re) / re;
}

double xi1_parmar(double m, double re) {
  return re_cd_parmar(m, re) / re_cd_standard(re);
}

double xi2(double alpha_g, const VolumeFractionCorrection& c) {
  const double phi = std::clamp(1.0 - alpha_g, 0.0, c.phi_cap);
  switch (c.kind) {
    case VolumeFractionCorrection::Kind::None:
    case VolumeFractionCorrection::Kind::Tenneti:
    case VolumeFractionCorrection::Kind::Osnes:
      return 1.0;
    case VolumeFractionCorrection::Kind::Linear:
      return 1.0 + 5.94 * phi;
    case VolumeFractionCorrection::Kind::Sangani:
      break;
  }
  const double ag = 1.0 - phi;
  return (1.0 + 2.0 * phi) / (ag * ag * ag);
}

double drag_coefficient(const GasAtParcel& g, double slip, double d, bool compressible,
                        const VolumeFractionCorrection& c) {
  const double re = g.rho * slip * d / g.mu;
  if (c.kind == VolumeFractionCorrection::Kind::Tenneti ||
      c.kind == VolumeFractionCorrection::Kind::Osnes) {
    const double phi = std::clamp(1.0 - g.alpha_g, 0.0, c.phi_cap);
    const double f =
        c.kind == VolumeFractionCorrection::Kind::Tenneti
            ? tenneti_drag_factor(re, phi)
            : osnes_drag_factor(re, slip / g.c, knudsen_number(g.rho, g.mu, g.c, d, g.gamma),
                                g.gamma, phi);
    return 3.0 * kPi * g.mu * d * f;
  }
  const double re_cd = compressible ? re_cd_parmar(slip / g.c, re) : re_cd_standard(re);
  return 3.0 * kPi * g.mu * d * re_cd / 24.0 * xi2(g.alpha_g, c);
}

Vec2 drag_force(const GasAtParcel& g, Vec2 up, double d, const VolumeFractionCorrection& c) {
  const Vec2 ur = g.u - up;
  return linear_drag(drag_coefficient(g, ur.norm(), d, true, c), ur);
}

}  // namespace dustlift::aero
