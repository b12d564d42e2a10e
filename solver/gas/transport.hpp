#pragma once
// Gas transport properties (paper section 2.1; docs/gas-solver.md):
//  - Constant: mu fixed, lambda = mu cp(T) / Pr;
//  - Sutherland: mu = mu_ref (T/T_ref)^{3/2} (T_ref + S)/(T + S), lambda = mu cp(T) / Pr;
//  - GordonWilke: per-species fits ln(eta) = A ln T + B/T + C/T^2 + D (Gordon, McBride &
//    Zeleznik 1984 / NASA CEA trans.inp) mixed by Wilke's rule (Wilke 1950) for O2:N2 = 1:3.76.
// Inviscid returns zeros (the solver then skips the viscous terms entirely).
#include <cstddef>
#include <vector>

#include "solver/gas/gas_config.hpp"

namespace dustlift {

/// Dynamic viscosity (Pa s) and thermal conductivity (W/(m K)).
struct TransportProperties {
  double mu = 0.0;
  double lambda = 0.0;
};

/// One Gordon fit: ln(eta) = A ln T + B/T + C/T^2 + D.
struct GordonFit {
  double A, B, C, D;
};

/// exp(A ln T + B/T + C/T^2 + D) (the fit's own units: micropoise or microW/(cm K)).
double evaluate_gordon_fit(const GordonFit& fit, double T);

/// Species properties from the CEA fits (200-1000 K and 1000-5000 K ranges), SI units.
TransportProperties nitrogen_transport(double T);
TransportProperties oxygen_transport(double T);

/// Wilke's mixing rule for a binary mixture of mole fractions x1, x2 and molar masses m1, m2.
/// The same viscosity-based Phi_ij also mixes the conductivities (docs/gas-solver.md).
TransportProperties wilke_binary_mixture(const TransportProperties& s1, double x1, double m1,
                                         const TransportProperties& s2, double x2, double m2);

/// Air (O2:N2 = 1:3.76) by Gordon fits + Wilke.
TransportProperties air_transport_gordon_wilke(double T);

/// air_transport_gordon_wilke tabulated at 1 K spacing on [20 K, 6000 K] with linear
/// interpolation, for the per-cell loops (4 exp + 1 log + Wilke per cell cost more than the
/// whole inviscid flux). Interpolation error < 3e-6 relative in the fits' range (T >= 200 K),
/// < 2e-5 above 100 K (unit-tested), far below the fits' own uncertainty; outside the table
/// the fits are evaluated directly.
class GordonWilkeAirTable {
 public:
  GordonWilkeAirTable();
  TransportProperties operator()(double T) const {
    const double x = (T - kTmin) * kInvStep;
    if (!(x >= 0.0 && x < static_cast<double>(count_ - 1))) return air_transport_gordon_wilke(T);
    const auto k = static_cast<std::size_t>(x);
    const double w = x - static_cast<double>(k);
    return {mu_[k] + w * (mu_[k + 1] - mu_[k]), lambda_[k] + w * (lambda_[k + 1] - lambda_[k])};
  }
  /// The same for n temperatures (a row of cells): mu[i], lambda[i] of T[i] (transport_rows.cpp,
  /// vectorised; values identical to operator()).
  void apply(const double* T, double* mu, double* lambda, int n) const;
  /// The largest mu and the largest lambda operator() gives for any T in [t_lo, t_hi] (the
  /// interpolation is linear between nodes, so they are at nodes or at the ends); infinite
  /// when the interval leaves the table.
  TransportProperties largest_over(double t_lo, double t_hi) const;

 private:
  static constexpr double kTmin = 20.0, kTmax = 6000.0, kInvStep = 1.0;  // 1 K spacing
  std::size_t count_;
  std::vector<double> mu_, lambda_;
};

/// Sutherland's law for the viscosity.
double sutherland_viscosity(double T, const TransportConfig& c);

/// The configured model at temperature T, where `cp` is the gas's cp(T) (used for lambda
/// of the Constant and Sutherland models).
inline TransportProperties transport_properties(const TransportConfig& c, double T, double cp) {
  switch (c.model) {
    case TransportModel::Inviscid:
      return {};
    case TransportModel::Constant:
      return {c.viscosity, c.viscosity * cp / c.prandtl};
    case TransportModel::Sutherland: {
      const double mu = sutherland_viscosity(T, c);
      return {mu, mu * cp / c.prandtl};
    }
    case TransportModel::GordonWilke:
      return air_transport_gordon_wilke(T);
  }
  return {};
}

}  // namespace dustlift
