#pragma once
// Linear spring–dashpot contact (paper Table 1; docs/dem.md).
// Pure functions: the closed-form restitution and contact time of the law, and the
// 2-D contact kernel shared by parcel–parcel and parcel–wall contacts.
#include <cmath>
#include <numbers>

namespace dustlift {

/// Linear spring–dashpot contact law (Table 1), per REAL particle (docs/dem.md).
struct ContactParams {
  double k_n = 5e4;       ///< N/m, normal spring
  double k_t = 100.0;     ///< N/m, tangential spring (paper's "k_n/k_t = 0.002" read as k_t/k_n)
  double damping = 1e-4;  ///< N s/m, dashpot h, same normal and tangential (paper)
  /// Coulomb limit |F_t| <= mu |F_n|; infinity switches the limit off (the paper's Table 1).
  double friction = 0.5;
  /// The material's normal restitution e_n when the scene gives it: the dashpot then follows
  /// for each pair's reduced mass (pair_damping); 0: the dashpot `damping` is given.
  double restitution = 0.0;
};

/// Damping ratio zeta = h / (2 sqrt(m_eff k_n)) of the overlap ODE m_eff d'' + h d' + k_n d = 0.
inline double contact_damping_ratio(double m_eff, double k_n, double h) {
  return h / (2.0 * std::sqrt(m_eff * k_n));
}

/// Normal restitution e_n = exp(-pi zeta / sqrt(1 - zeta^2)) of the linear law (§3.6).
inline double contact_restitution(double m_eff, double k_n, double h) {
  const double z = contact_damping_ratio(m_eff, k_n, h);
  return std::exp(-std::numbers::pi * z / std::sqrt(1.0 - z * z));
}

/// Contact duration t_c = pi / sqrt(k_n/m_eff - (h / 2 m_eff)^2) (overlap returns to zero).
inline double contact_duration(double m_eff, double k_n, double h) {
  const double g = h / (2.0 * m_eff);
  return std::numbers::pi / std::sqrt(k_n / m_eff - g * g);
}

/// Dashpot h that gives restitution e_n (inverse of contact_restitution).
inline double damping_for_restitution(double m_eff, double k_n, double e_n) {
  const double l = std::log(e_n);
  return -2.0 * l * std::sqrt(m_eff * k_n) / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

/// c(e) = 2 (-ln e) / sqrt(pi^2 + ln^2 e): the dashpot h = c(e) sqrt(m_eff k_n) gives the
/// restitution e to a pair of reduced mass m_eff (e = 1: c = 0, no dashpot).
inline double restitution_damping_factor(double e_n) {
  const double l = std::log(e_n);
  return -2.0 * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

/// The dashpot of one pair (or of a parcel at a wall, m_eff its real particle's mass) for the
/// restitution whose factor is c = restitution_damping_factor(e): h = c sqrt(m_eff k_n).
inline double pair_damping(double factor, double m_eff, double k_n) {
  return factor * std::sqrt(m_eff * k_n);
}

/// The mass of the overlap ODE m_eff d'' + h d' + k_n d = 0 of two parcels holding n_i, n_j
/// real particles of masses m_i, m_j under the pair rule (a pair stands for min(n_i, n_j) real
/// contacts; docs/dem.md): m_eff = 1 / (min(n_i, n_j) (1/(n_i m_i) + 1/(n_j m_j))). For equal
/// counts it is the real particles' reduced mass m_i m_j / (m_i + m_j); `inv_m` are 1/m.
inline double pair_effective_mass(double inv_m_i, double inv_m_j, double n_i, double n_j) {
  if (n_i == n_j) return 1.0 / (inv_m_i + inv_m_j);
  const double n = n_i < n_j ? n_i : n_j;
  return 1.0 / (n * (inv_m_i / n_i + inv_m_j / n_j));
}

/// Result of one contact evaluated from particle i's side.
struct ContactResult {
  double fx, fy;   ///< force on i (per real particle), N
  double torque;   ///< z torque on i, N m (lever arm r_i)
  double delta_t;  ///< tangential spring elongation to store for the next step, m
};

/// One contact seen from i. (nx, ny): unit normal from i to the partner; overlap > 0;
/// (ux, uy): relative velocity of the partner's surface w.r.t. i's surface at the contact,
/// u_ij = u_j - u_i - (r_i w_i + r_j w_j) z x n (§3.6); delta_t: stored tangential
/// elongation along t = z x n = (-ny, nx); r_i: i's lever arm; dt: step for the update.
///   F_n on i = -k_n overlap n + h (u_ij . n) n
///   F_t on i = (+k_t delta_t + h u_t) t, capped at mu |F_n|; the stored elongation grows
///              by u_t dt and is capped at mu |F_n| / k_t (with these two caps the tangential
///              contact can only dissipate energy; docs/dem.md)
///   torque on i = r_i (n x F_t)_z = r_i F_t   (n x t = z)
/// The scalar elongation follows the normal as it rotates (2-D: no re-projection needed);
/// it is symmetric in i and j, so both sides store the same history bit for bit.
inline ContactResult contact_force(const ContactParams& p, double nx, double ny, double overlap,
                                   double ux, double uy, double delta_t, double r_i, double dt) {
  const double u_n = ux * nx + uy * ny;
  const double u_t = -ux * ny + uy * nx;
  const double f_n = -p.k_n * overlap + p.damping * u_n;  // along n; < 0 pushes i away
  double f_t = p.k_t * delta_t + p.damping * u_t;
  double next_delta = delta_t + u_t * dt;
  const double f_max = p.friction * std::fabs(f_n);
  if (std::fabs(f_t) > f_max) f_t = std::copysign(f_max, f_t);  // sliding
  // The spring alone never holds more than the Coulomb force: it then neither stores
  // energy the contact could not transmit nor grows while the pair slides.
  if (std::fabs(p.k_t * next_delta) > f_max) next_delta = std::copysign(f_max / p.k_t, next_delta);
  return {f_n * nx - f_t * ny, f_n * ny + f_t * nx, r_i * f_t, next_delta};
}

}  // namespace dustlift
