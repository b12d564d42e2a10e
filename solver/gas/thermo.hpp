#pragma once
// Gas thermodynamics (paper eq. 4 and section 2.1): p = rho R T with either
//  - a calorically perfect gas (constant gamma), or
//  - thermally perfect air, O2:N2 = 1:3.76 by mole, cp(T) from NASA 7-coefficient
//    polynomials (McBride, Gordon & Reno 1993, NASA TM-4513; docs/gas-solver.md).
// Both expose the same inline interface so the solver's loops are templated on the model
// (chosen once at construction, no per-cell virtual call).
//
// Energy reference: internal energies are sensible, e(0) = 0 for the calorically perfect gas
// and e = h - RT with the low-range formation constant a6 removed for air, so e > 0 for T > 0
// and a negative e maps to a negative T (caught as p <= 0 by the solver's checks).
#include <algorithm>
#include <array>
#include <cmath>

namespace dustlift {

/// Universal gas constant, J/(mol K) (CODATA 2018).
inline constexpr double kUniversalGasConstant = 8.314462618;

/// gamma-law gas: cv, cp constant.
class CaloricallyPerfectGas {
 public:
  CaloricallyPerfectGas(double gamma, double gas_constant)
      : gamma_(gamma), R_(gas_constant), cv_(gas_constant / (gamma - 1.0)), cp_(gamma * cv_) {}

  double gas_constant() const { return R_; }
  double cp(double /*T*/) const { return cp_; }
  double cv(double /*T*/) const { return cv_; }
  double gamma(double /*T*/) const { return gamma_; }
  double internal_energy(double T) const { return cv_ * T; }
  double enthalpy(double T) const { return cp_ * T; }
  /// Exact inverse of internal_energy (the guess is unused).
  double temperature(double e, double /*guess*/) const { return e / cv_; }
  double sound_speed_squared(double T) const { return gamma_ * R_ * T; }
  /// Batch form of temperature() over a row (same interface as ThermallyPerfectAir's).
  void temperatures(const double* e, const double* /*guess*/, double* T, int n) const {
    for (int i = 0; i < n; ++i) T[i] = e[i] / cv_;
  }
  /// h(T) and cp(T) together (what a face flux needs).
  void enthalpy_and_cp(double T, double& h, double& cp) const {
    h = cp_ * T;
    cp = cp_;
  }

 private:
  double gamma_, R_, cv_, cp_;
};

/// NASA 7-coefficient polynomial of one temperature range.
struct Nasa7 {
  std::array<double, 7> a;
};

/// NASA TM-4513 coefficients (docs/gas-solver.md), ranges 200-1000 K and 1000-6000 K.
namespace nasa7 {
inline constexpr Nasa7 kN2Low{{3.53100528E+00, -1.23660987E-04, -5.02999437E-07, 2.43530612E-09,
                               -1.40881235E-12, -1.04697628E+03, 2.96747468E+00}};
inline constexpr Nasa7 kN2High{{2.95257626E+00, 1.39690057E-03, -4.92631691E-07, 7.86010367E-11,
                                -4.60755321E-15, -9.23948645E+02, 5.87189252E+00}};
inline constexpr Nasa7 kO2Low{{3.78245636E+00, -2.99673415E-03, 9.84730200E-06, -9.68129508E-09,
                               3.24372836E-12, -1.06394356E+03, 3.65767573E+00}};
inline constexpr Nasa7 kO2High{{3.66096083E+00, 6.56365523E-04, -1.41149485E-07, 2.05797658E-11,
                                -1.29913248E-15, -1.21597725E+03, 3.41536184E+00}};
inline constexpr double kRangeBreak = 1000.0;  ///< K
inline constexpr double kMoleFractionO2 = 1.0 / 4.76;
inline constexpr double kMoleFractionN2 = 3.76 / 4.76;
inline constexpr double kMolarMassO2 = 31.9988e-3;  ///< kg/mol
inline constexpr double kMolarMassN2 = 28.0134e-3;  ///< kg/mol

/// cp/R of one polynomial.
constexpr double cp_over_r(const Nasa7& c, double T) {
  return c.a[0] + T * (c.a[1] + T * (c.a[2] + T * (c.a[3] + T * c.a[4])));
}
/// h/R (K) of one polynomial, absolute (formation enthalpy included through a6).
constexpr double h_over_r(const Nasa7& c, double T) {
  return T * (c.a[0] + T * (c.a[1] / 2 + T * (c.a[2] / 3 + T * (c.a[3] / 4 + T * c.a[4] / 5)))) + c.a[5];
}
/// Mole-weighted mixture polynomial (cp/R and h/R of a mixture are mole averages).
constexpr Nasa7 air_mixture(const Nasa7& o2, const Nasa7& n2) {
  Nasa7 m{};
  for (int k = 0; k < 7; ++k) m.a[k] = kMoleFractionO2 * o2.a[k] + kMoleFractionN2 * n2.a[k];
  return m;
}
inline constexpr Nasa7 kAirLow = air_mixture(kO2Low, kN2Low);
inline constexpr Nasa7 kAirHigh = air_mixture(kO2High, kN2High);
}  // namespace nasa7

/// Thermally perfect air (O2:N2 = 1:3.76), R from the config (288.190 J/(kg K) by default).
class ThermallyPerfectAir {
 public:
  static constexpr double kTmin = 20.0;    ///< K, below: linear extrapolation of e(T)
  static constexpr double kTmax = 6000.0;  ///< K, above: constant cv extrapolation

  explicit ThermallyPerfectAir(double gas_constant = 288.190)
      : R_(gas_constant), e_min_(internal_energy(kTmin)), e_max_(internal_energy(kTmax)),
        cv_max_(cv(kTmax)) {}

  double gas_constant() const { return R_; }
  double cp(double T) const { return R_ * nasa7::cp_over_r(range(T), T); }
  double cv(double T) const { return cp(T) - R_; }
  double gamma(double T) const {
    const double c = cp(T);
    return c / (c - R_);
  }
  /// Sensible enthalpy: absolute h minus the constant R*a6 of the low range (h(0) = 0).
  double enthalpy(double T) const {
    return R_ * (nasa7::h_over_r(range(T), T) - nasa7::kAirLow.a[5]);
  }
  /// Absolute enthalpy of the NASA polynomials (h(298.15 K) ~ 0, reference elements).
  double absolute_enthalpy(double T) const { return R_ * nasa7::h_over_r(range(T), T); }
  double internal_energy(double T) const { return enthalpy(T) - R_ * T; }
  double sound_speed_squared(double T) const { return gamma(T) * R_ * T; }
  /// Same values as enthalpy() and cp(); the range is chosen by selects (no branch) so that
  /// face loops vectorise.
  void enthalpy_and_cp(double T, double& h, double& cp) const {
    // Both ranges evaluated, then one select: branch-free, so face loops vectorise.
    using nasa7::kAirHigh;
    using nasa7::kAirLow;
    const double cp_low = nasa7::cp_over_r(kAirLow, T), cp_high = nasa7::cp_over_r(kAirHigh, T);
    const double h_low = nasa7::h_over_r(kAirLow, T) - kAirLow.a[5];
    const double h_high = nasa7::h_over_r(kAirHigh, T) - kAirLow.a[5];
    const bool low = T < nasa7::kRangeBreak;
    cp = R_ * (low ? cp_low : cp_high);
    h = R_ * (low ? h_low : h_high);
  }

  /// enthalpy_and_cp() for T below the range break (1000 K), where it gives the same values.
  void enthalpy_and_cp_low(double T, double& h, double& cp) const {
    using nasa7::kAirLow;
    cp = R_ * nasa7::cp_over_r(kAirLow, T);
    h = R_ * (nasa7::h_over_r(kAirLow, T) - kAirLow.a[5]);
  }
  /// Temperature below which only the low-range polynomials are needed.
  static constexpr double low_range_limit() { return nasa7::kRangeBreak; }

  /// temperature() for a row of n cells: e and guesses in, T out (T may alias neither).
  /// Two branch-free Newton steps for all cells (vectorised; defined in thermo_batch.cpp),
  /// accepted where the second step was below 1e-7 T inside the bracket, else the
  /// safeguarded scalar solve. Results agree with temperature() to ~1e-14 relative.
  void temperatures(const double* e, const double* guess, double* T, int n) const;

  /// T from e(T) = h(T) - RT: Newton warm-started at `guess`, kept inside a shrinking
  /// bracket [lo, hi] and replaced by bisection whenever it would leave it.
  /// NaN in gives NaN out; e <= 0 gives T <= 0 (the caller reports it).
  double temperature(double e, double guess) const {
    if (!(e > e_min_)) return kTmin * e / e_min_;
    if (e > e_max_) return kTmax + (e - e_max_) / cv_max_;
    double lo = kTmin, hi = kTmax;
    double T = (guess > lo && guess < hi) ? guess : 300.0;
    for (int iter = 0; iter < 100; ++iter) {
      const Nasa7& c = range(T);
      const double f = R_ * (nasa7::h_over_r(c, T) - nasa7::kAirLow.a[5] - T) - e;
      if (f > 0) {
        hi = T;
      } else {
        lo = T;
      }
      const double newton = T - f / (R_ * (nasa7::cp_over_r(c, T) - 1.0));
      if (newton > lo && newton < hi) {
        // Quadratic convergence: after a Newton step of 1e-7 T the error of the new iterate
        // is ~1e-14 T (|cv'/cv| T ~ 0.1 for air).
        if (std::abs(newton - T) <= 1e-7 * T) return newton;
        T = newton;
      } else {
        T = 0.5 * (lo + hi);  // bisection keeps the bracket shrinking
      }
    }
    return T;
  }

 private:
  static const Nasa7& range(double T) { return T < nasa7::kRangeBreak ? nasa7::kAirLow : nasa7::kAirHigh; }
  double R_;
  double e_min_, e_max_, cv_max_;
};

}  // namespace dustlift
