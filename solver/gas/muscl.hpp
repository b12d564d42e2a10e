#pragma once
// MUSCL reconstruction of one primitive variable at a face (van Leer; docs/gas-solver.md),
// in index space so that it applies unchanged on the stretched grid.
// Face i+1/2 lies between cells i and i+1; the stencil is q_{i-1}, q_i, q_{i+1}, q_{i+2}.
//   q^L = q_i     + 1/4 [(1-k) D-~_i     + (1+k) D+~_i]
//   q^R = q_{i+1} - 1/4 [(1-k) D+~_{i+1} + (1+k) D-~_{i+1}]
// minmod-type limiting with compression b: D-~ = minmod(D-, b D+), D+~ = minmod(D+, b D-),
// 1 <= b <= (3-k)/(1-k); or van Albada's smooth limiter s = (2 D+ D- + e)/(D+^2 + D-^2 + e).
#include <algorithm>
#include <cmath>

#include "solver/gas/gas_config.hpp"

namespace dustlift {

/// Reconstruction settings resolved from SchemeConfig.
struct MusclSettings {
  Reconstruction order = Reconstruction::Muscl3;
  Limiter limiter = Limiter::Minmod;
  double kappa = 1.0 / 3.0;
  double b = 2.0;
};

/// kappa of each order: first order none; Muscl2 the fully upwind kappa = -1 scheme;
/// Muscl3 kappa = 1/3 (third-order upwind-biased, the paper's "third-order SLAU2").
/// minmod_b is clamped to the TVD bound (3 - kappa)/(1 - kappa) of the chosen kappa.
inline MusclSettings muscl_settings(const SchemeConfig& s) {
  MusclSettings m;
  m.order = s.reconstruction;
  m.limiter = s.limiter;
  m.kappa = s.reconstruction == Reconstruction::Muscl2 ? -1.0 : 1.0 / 3.0;
  // The scene allows b up to 4 (the kappa = 1/3 bound); beyond (3-k)/(1-k) the face values
  // could leave the range of the neighbouring cells, so clamp (kappa = -1: b <= 2).
  m.b = std::min(s.minmod_b, (3.0 - m.kappa) / (1.0 - m.kappa));
  return m;
}

/// minmod(a, b): the smaller-magnitude argument when both have the same sign, else 0.
/// Written as selects so that row loops vectorise.
inline double minmod(double a, double b) {
  const double smaller = std::abs(a) < std::abs(b) ? a : b;
  return a * b <= 0.0 ? 0.0 : smaller;
}

/// Both face values of cell q at once, its right face (plus) and its left face (minus):
/// the limited slopes computed once for both (x-face rows, flux_rows_kernels.hpp).
template <Limiter L>
inline void muscl_extrapolation_pair(double q, double dm, double dp, double kappa, double b, double& plus,
                                     double& minus) {
  const double k = kappa;
  if constexpr (L == Limiter::Minmod) {
    const double dm_lim = minmod(dm, b * dp);
    const double dp_lim = minmod(dp, b * dm);
    plus = q + 0.25 * ((1.0 - k) * dm_lim + (1.0 + k) * dp_lim);
    minus = q - 0.25 * ((1.0 - k) * dp_lim + (1.0 + k) * dm_lim);
  } else {
    // van Albada: epsilon relative to the local scale guards 0/0 on flat data only.
    const double eps = 1e-12 * (q * q) + 1e-300;
    const double s = std::max(0.0, (2.0 * dp * dm + eps) / (dp * dp + dm * dm + eps));
    plus = q + 0.25 * s * ((1.0 - k * s) * dm + (1.0 + k * s) * dp);
    minus = q - 0.25 * s * ((1.0 - k * s) * dp + (1.0 + k * s) * dm);
  }
}

/// Extrapolated value of cell q (backward difference dm, forward difference dp) at its
/// face on side Side (+1: right face, -1: left face), limiter fixed at compile time. (The
/// other face's value is dead code once inlined.)
template <Limiter L, int Side>
inline double muscl_extrapolate(double q, double dm, double dp, double kappa, double b) {
  double plus = 0.0, minus = 0.0;
  muscl_extrapolation_pair<L>(q, dm, dp, kappa, b, plus, minus);
  return Side > 0 ? plus : minus;
}

/// Run-time dispatching form of the above (side +1 or -1).
inline double muscl_extrapolate(double q, double dm, double dp, int side, const MusclSettings& m) {
  if (m.limiter == Limiter::Minmod) {
    return side > 0 ? muscl_extrapolate<Limiter::Minmod, +1>(q, dm, dp, m.kappa, m.b)
                    : muscl_extrapolate<Limiter::Minmod, -1>(q, dm, dp, m.kappa, m.b);
  }
  return side > 0 ? muscl_extrapolate<Limiter::VanAlbada, +1>(q, dm, dp, m.kappa, m.b)
                  : muscl_extrapolate<Limiter::VanAlbada, -1>(q, dm, dp, m.kappa, m.b);
}

/// Left and right values at face i+1/2 from q_{i-1}, q_i, q_{i+1}, q_{i+2}.
struct FacePair {
  double left, right;
};

inline FacePair muscl_face(double qm1, double q0, double qp1, double qp2, const MusclSettings& m) {
  if (m.order == Reconstruction::FirstOrder) return {q0, qp1};
  return {muscl_extrapolate(q0, q0 - qm1, qp1 - q0, +1, m),
          muscl_extrapolate(qp1, qp1 - q0, qp2 - qp1, -1, m)};
}

}  // namespace dustlift
