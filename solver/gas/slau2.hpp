#pragma once
// SLAU2 numerical flux (Kitamura & Shima 2013, JCP 245, 62-83; docs/gas-solver.md):
// a pure function of the reconstructed left/right states and the unit face normal.
#include <algorithm>
#include <cmath>

namespace dustlift {

/// A face-side state: primitives plus total enthalpy H = h + |u|^2/2 and sound speed c.
struct FaceState {
  double rho, u, v, p, H, c;
};

/// Flux through a unit face per unit area (mass, x/y momentum, energy).
struct ConservedFlux {
  double mass, momentum_x, momentum_y, energy;
};

/// SLAU2 flux with the pressure part kept apart: momentum_x/y hold only the convective
/// part (mdot-upwinded velocity) and `pressure` is the face pressure p~, so that the full
/// momentum flux is momentum + p~ n. The solver needs p~ alone for the well-balanced
/// porosity term alpha grad p (see GasSolver, docs/gas-solver.md).
struct SplitFlux {
  double mass, momentum_x, momentum_y, energy, pressure;
};

/// SLAU2 from left state L to right state R across the face with unit normal (nx, ny)
/// (pointing from L to R), pressure part apart (see SplitFlux).
inline SplitFlux slau2_split_flux(const FaceState& L, const FaceState& R, double nx, double ny) {
  const double vn_l = L.u * nx + L.v * ny;
  const double vn_r = R.u * nx + R.v * ny;
  const double c_bar = 0.5 * (L.c + R.c);
  const double inv_c_bar = 1.0 / c_bar;
  const double m_l = vn_l * inv_c_bar;
  const double m_r = vn_r * inv_c_bar;
  const double rho_bar = 0.5 * (L.rho + R.rho);
  const double speed = std::sqrt(0.5 * (L.u * L.u + L.v * L.v + R.u * R.u + R.v * R.v));
  const double m_hat = std::min(1.0, speed * inv_c_bar);
  const double chi = (1.0 - m_hat) * (1.0 - m_hat);
  const double g = -std::max(std::min(m_l, 0.0), -1.0) * std::min(std::max(m_r, 0.0), 1.0);
  const double abs_vn_l = std::abs(vn_l), abs_vn_r = std::abs(vn_r);
  const double vn_bar = (L.rho * abs_vn_l + R.rho * abs_vn_r) / (L.rho + R.rho);
  const double vn_plus = (1.0 - g) * vn_bar + g * abs_vn_l;
  const double vn_minus = (1.0 - g) * vn_bar + g * abs_vn_r;
  const double mdot =
      0.5 * (L.rho * (vn_l + vn_plus) + R.rho * (vn_r - vn_minus) - chi * inv_c_bar * (R.p - L.p));
  // Pressure polynomials P+(M_L), P-(M_R) (written as selects so that face loops vectorise).
  const double p_plus_sub = 0.25 * (m_l + 1.0) * (m_l + 1.0) * (2.0 - m_l);
  const double p_plus_sup = m_l > 0.0 ? 1.0 : 0.0;
  const double p_plus = std::abs(m_l) < 1.0 ? p_plus_sub : p_plus_sup;
  const double p_minus_sub = 0.25 * (m_r - 1.0) * (m_r - 1.0) * (2.0 + m_r);
  const double p_minus_sup = m_r < 0.0 ? 1.0 : 0.0;
  const double p_minus = std::abs(m_r) < 1.0 ? p_minus_sub : p_minus_sup;
  // At rest with p_L = p_R every correction term is exactly zero, so p~ = p to the last bit.
  const double p_tilde = 0.5 * (L.p + R.p) + 0.5 * (p_plus - p_minus) * (L.p - R.p) +
                         speed * (p_plus + p_minus - 1.0) * rho_bar * c_bar;
  const double m_plus = 0.5 * (mdot + std::abs(mdot));
  const double m_minus = 0.5 * (mdot - std::abs(mdot));
  return {mdot, m_plus * L.u + m_minus * R.u, m_plus * L.v + m_minus * R.v, m_plus * L.H + m_minus * R.H,
          p_tilde};
}

/// SLAU2 flux from left state L to right state R across the face with unit normal (nx, ny)
/// (pointing from L to R).
inline ConservedFlux slau2_flux(const FaceState& L, const FaceState& R, double nx, double ny) {
  const SplitFlux f = slau2_split_flux(L, R, nx, ny);
  return {f.mass, f.momentum_x + f.pressure * nx, f.momentum_y + f.pressure * ny, f.energy};
}

/// The physical (Euler) flux of one state, for consistency checks.
inline ConservedFlux euler_flux(const FaceState& s, double nx, double ny) {
  const double vn = s.u * nx + s.v * ny;
  const double m = s.rho * vn;
  return {m, m * s.u + s.p * nx, m * s.v + s.p * ny, m * s.H};
}

}  // namespace dustlift
