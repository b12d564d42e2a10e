#include "solver/gas/transport.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/gas/thermo.hpp"

namespace dustlift {
namespace {

// NASA CEA trans.inp coefficients (docs/gas-solver.md).
constexpr GordonFit kN2ViscosityLow{0.62526577, -31.779652, -1640.7983, 1.7454992};
constexpr GordonFit kN2ViscosityHigh{0.87395209, 561.52222, -173948.09, -0.39335958};
constexpr GordonFit kN2ConductivityLow{0.85439436, 105.73224, -12347.848, 0.47793128};
constexpr GordonFit kN2ConductivityHigh{0.88407146, 133.57293, -11429.64, 0.24417019};
constexpr GordonFit kO2ViscosityLow{0.60916180, -52.244847, -599.74009, 2.0410801};
constexpr GordonFit kO2ViscosityHigh{0.72216486, 175.50839, -57974.816, 1.0901044};
constexpr GordonFit kO2ConductivityLow{0.77229167, 6.8463210, -5893.3377, 1.2210365};
constexpr GordonFit kO2ConductivityHigh{0.90917351, 291.24182, -79650.171, 0.064851631};

constexpr double kMicropoiseToPaS = 1e-7;
constexpr double kMicroWattPerCmKToSI = 1e-4;
constexpr double kFitRangeBreak = 1000.0;  // K

TransportProperties species(double T, const GordonFit& mu_low, const GordonFit& mu_high,
                            const GordonFit& k_low, const GordonFit& k_high) {
  const bool low = T < kFitRangeBreak;
  return {kMicropoiseToPaS * evaluate_gordon_fit(low ? mu_low : mu_high, T),
          kMicroWattPerCmKToSI * evaluate_gordon_fit(low ? k_low : k_high, T)};
}

/// Wilke's Phi_ij (Wilke 1950).
double wilke_phi(double mu_i, double mu_j, double m_i, double m_j) {
  const double a = 1.0 + std::sqrt(mu_i / mu_j) * std::sqrt(std::sqrt(m_j / m_i));
  return a * a / std::sqrt(8.0 * (1.0 + m_i / m_j));
}

}  // namespace

double evaluate_gordon_fit(const GordonFit& f, double T) {
  const double inv = 1.0 / T;
  return std::exp(f.A * std::log(T) + inv * (f.B + f.C * inv) + f.D);
}

TransportProperties nitrogen_transport(double T) {
  return species(T, kN2ViscosityLow, kN2ViscosityHigh, kN2ConductivityLow, kN2ConductivityHigh);
}

TransportProperties oxygen_transport(double T) {
  return species(T, kO2ViscosityLow, kO2ViscosityHigh, kO2ConductivityLow, kO2ConductivityHigh);
}

TransportProperties wilke_binary_mixture(const TransportProperties& s1, double x1, double m1,
                                         const TransportProperties& s2, double x2, double m2) {
  const double phi12 = wilke_phi(s1.mu, s2.mu, m1, m2);
  const double phi21 = wilke_phi(s2.mu, s1.mu, m2, m1);
  const double d1 = x1 + x2 * phi12;  // sum_j x_j Phi_1j with Phi_11 = 1
  const double d2 = x2 + x1 * phi21;
  return {x1 * s1.mu / d1 + x2 * s2.mu / d2, x1 * s1.lambda / d1 + x2 * s2.lambda / d2};
}

TransportProperties air_transport_gordon_wilke(double T) {
  // Same values as wilke_binary_mixture(oxygen_transport(T), ..., nitrogen_transport(T), ...),
  // arranged for the per-cell loop: one log for the four fits, molar-mass factors of Phi_ij
  // computed once.
  struct WilkeConstants {
    double k12, k21, s12, s21;  // (M_j/M_i)^(1/4) and sqrt(8 (1 + M_i/M_j)), 1 = O2, 2 = N2
  };
  static const WilkeConstants w = [] {
    const double m1 = nasa7::kMolarMassO2, m2 = nasa7::kMolarMassN2;
    return WilkeConstants{std::sqrt(std::sqrt(m2 / m1)), std::sqrt(std::sqrt(m1 / m2)),
                          std::sqrt(8.0 * (1.0 + m1 / m2)), std::sqrt(8.0 * (1.0 + m2 / m1))};
  }();
  const bool low = T < kFitRangeBreak;
  const double ln_t = std::log(T), inv = 1.0 / T;
  auto fit = [&](const GordonFit& f) {
    return std::exp(f.A * ln_t + inv * (f.B + f.C * inv) + f.D);
  };
  const double mu1 = kMicropoiseToPaS * fit(low ? kO2ViscosityLow : kO2ViscosityHigh);
  const double mu2 = kMicropoiseToPaS * fit(low ? kN2ViscosityLow : kN2ViscosityHigh);
  const double k1 = kMicroWattPerCmKToSI * fit(low ? kO2ConductivityLow : kO2ConductivityHigh);
  const double k2 = kMicroWattPerCmKToSI * fit(low ? kN2ConductivityLow : kN2ConductivityHigh);
  const double r = std::sqrt(mu1 / mu2);
  const double a12 = 1.0 + r * w.k12, a21 = 1.0 + w.k21 / r;
  const double phi12 = a12 * a12 / w.s12, phi21 = a21 * a21 / w.s21;
  const double x1 = nasa7::kMoleFractionO2, x2 = nasa7::kMoleFractionN2;
  const double d1 = x1 + x2 * phi12, d2 = x2 + x1 * phi21;
  return {x1 * mu1 / d1 + x2 * mu2 / d2, x1 * k1 / d1 + x2 * k2 / d2};
}

GordonWilkeAirTable::GordonWilkeAirTable()
    : count_(static_cast<std::size_t>((kTmax - kTmin) * kInvStep) + 1),
      mu_(count_),
      lambda_(count_) {
  for (std::size_t k = 0; k < count_; ++k) {
    const TransportProperties p =
        air_transport_gordon_wilke(kTmin + static_cast<double>(k) / kInvStep);
    mu_[k] = p.mu;
    lambda_[k] = p.lambda;
  }
}

TransportProperties GordonWilkeAirTable::largest_over(double t_lo, double t_hi) const {
  const double x_lo = (t_lo - kTmin) * kInvStep, x_hi = (t_hi - kTmin) * kInvStep;
  const double last = static_cast<double>(count_ - 1);
  if (!(x_lo >= 0.0 && x_hi < last && x_lo <= x_hi)) {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf};
  }
  TransportProperties most = (*this)(t_lo);
  const TransportProperties end = (*this)(t_hi);
  most.mu = std::max(most.mu, end.mu);
  most.lambda = std::max(most.lambda, end.lambda);
  for (auto k = static_cast<std::size_t>(std::ceil(x_lo)); static_cast<double>(k) <= x_hi; ++k) {
    most.mu = std::max(most.mu, mu_[k]);
    most.lambda = std::max(most.lambda, lambda_[k]);
  }
  return most;
}

double sutherland_viscosity(double T, const TransportConfig& c) {
  const double r = T / c.sutherland_t_ref;
  return c.sutherland_mu_ref * r * std::sqrt(r) * (c.sutherland_t_ref + c.sutherland_s) /
         (T + c.sutherland_s);
}

}  // namespace dustlift
