// SSP-RK3 stage update of a row segment (stage_update.hpp). Compiled with -fno-math-errno
// -fno-trapping-math (solver/CMakeLists.txt) so that the select passes vectorise; neither
// option changes a computed value.
#include "solver/gas/stage_update.hpp"

#include <cmath>

#include "solver/gas/gas_components.hpp"
#include "solver/gas/thermo.hpp"

namespace dustlift {
namespace {

/// One variable's stage: rhs = -(F_{i+1} - F_i)/dx - (G_above - G_below)/dy + S (+ the
/// well-balanced pressure parts for the momenta), U <- U0 + c (U - U0 + dt rhs), and
/// changed[i] = 1 where U changed. One pass, so the rhs is never stored.
template <int PressureAxis>
[[gnu::noinline]] void variable_pass(
    const double* __restrict fx, const double* __restrict fy_below,
    const double* __restrict fy_above, const double* __restrict source,
    const double* __restrict inv_dx, double inv_dy, const double* __restrict p_face_lo,
    const double* __restrict p_face_hi, const double* __restrict a_lo, const double* __restrict a,
    const double* __restrict a_hi, const double* __restrict p, const double* __restrict u0,
    double* __restrict u, double* __restrict changed, double dt, double c, int n) {
  for (int i = 0; i < n; ++i) {
    double rhs =
        -(fx[i + 1] - fx[i]) * inv_dx[i] - (fy_above[i] - fy_below[i]) * inv_dy + source[i];
    if constexpr (PressureAxis != 0) {
      // a grad p in well-balanced form: with p~ = p_i at both faces exactly zero whatever
      // the face porosities. The faces are the row's x-faces (i, i+1) or the y-faces below
      // and above.
      const double a_plus = 0.5 * (a[i] + a_hi[i]), a_minus = 0.5 * (a_lo[i] + a[i]);
      const double h = PressureAxis == 1 ? inv_dx[i] : inv_dy;
      rhs -= (a_plus * (p_face_hi[i] - p[i]) - a_minus * (p_face_lo[i] - p[i])) * h;
    }
    const double q = u0[i] + c * ((u[i] - u0[i]) + dt * rhs);
    changed[i] = q != u[i] ? 1.0 : changed[i];
    u[i] = q;
  }
}

/// External sources plus the body force of gravity g on the stage state U = (a rho, a rho u,
/// a rho v, a E): the momenta's a rho g and the energy's a rho g.u, added to their sources in
/// `out` (the mass has no such term).
[[gnu::noinline]] void body_force_pass(const double* const* source, double* const* U, double gx,
                                       double gy, double* const* out, int n) {
  constexpr int kMX = Conserved::kMomentumX, kMY = Conserved::kMomentumY, kE = Conserved::kEnergy;
  const double* __restrict m = U[Conserved::kMass];
  const double* __restrict mx = U[kMX];
  const double* __restrict my = U[kMY];
  for (int i = 0; i < n; ++i) {
    out[kMX][i] = source[kMX][i] + m[i] * gx;
    out[kMY][i] = source[kMY][i] + m[i] * gy;
    out[kE][i] = source[kE][i] + mx[i] * gx + my[i] * gy;
  }
}

/// rho, u, v and the specific internal energy of the new state.
[[gnu::noinline]] void decode_pass(const double* __restrict m, const double* __restrict mx,
                                   const double* __restrict my, const double* __restrict en,
                                   const double* __restrict a, double* __restrict rho,
                                   double* __restrict u, double* __restrict v, double* __restrict e,
                                   int n) {
  for (int i = 0; i < n; ++i) {
    const double uu = mx[i] / m[i], vv = my[i] / m[i];
    rho[i] = m[i] / a[i];
    u[i] = uu;
    v[i] = vv;
    e[i] = en[i] / m[i] - 0.5 * (uu * uu + vv * vv);
  }
}

/// Writes the new primitives where the state changed; returns the first faulty cell or -1.
[[gnu::noinline]] int commit_pass(const double* __restrict changed,
                                  const double* __restrict new_rho, const double* __restrict new_u,
                                  const double* __restrict new_v, const double* __restrict new_T,
                                  double R, const double* __restrict m, const double* __restrict mx,
                                  const double* __restrict my, const double* __restrict en,
                                  double* __restrict rho, double* __restrict u,
                                  double* __restrict v, double* __restrict p, double* __restrict T,
                                  int n) {
  int bad_count = 0;
  for (int i = 0; i < n; ++i) {
    const bool c = changed[i] != 0.0;
    const double r = c ? new_rho[i] : rho[i];
    const double t = c ? new_T[i] : T[i];
    const double pp = c ? r * R * t : p[i];
    rho[i] = r;
    u[i] = c ? new_u[i] : u[i];
    v[i] = c ? new_v[i] : v[i];
    T[i] = t;
    p[i] = pp;
    // Finite conserved state, rho > 0, finite p > 0 (NaN fails every comparison).
    const double sum = m[i] + mx[i] + my[i] + en[i];
    const bool ok = (sum - sum == 0.0) && r > 0.0 && pp > 0.0 && pp - pp == 0.0;
    bad_count += ok ? 0 : 1;
  }
  if (bad_count == 0) return -1;
  for (int i = 0; i < n; ++i) {
    const double sum = m[i] + mx[i] + my[i] + en[i];
    if (!(std::isfinite(sum) && rho[i] > 0.0 && p[i] > 0.0 && std::isfinite(p[i]))) return i;
  }
  return -1;
}

/// The new state's primitives from its conserved state U and porosity: decoded, T(e)
/// warm-started at the current T, and written where the state changed; returns the first
/// faulty cell or -1.
template <class Thermo>
int new_primitives(const Thermo& th, const double* const* U, const double* alpha, double R,
                   const RowPrimitives& prim, const StageScratch& s, int n) {
  constexpr int kM = Conserved::kMass, kMX = Conserved::kMomentumX, kMY = Conserved::kMomentumY,
                kE = Conserved::kEnergy;
  decode_pass(U[kM], U[kMX], U[kMY], U[kE], alpha, s.rho, s.u, s.v, s.e, n);
  th.temperatures(s.e, prim.T, s.T, n);
  return commit_pass(s.changed, s.rho, s.u, s.v, s.T, R, U[kM], U[kMX], U[kMY], U[kE], prim.rho,
                     prim.u, prim.v, prim.p, prim.T, n);
}

}  // namespace

template <class Thermo>
int stage_update_row(const Thermo& th, const StageRow& r, const StageScratch& s, double dt,
                     double c_new) {
  const int n = r.n;
  if (n <= 0) return -1;
  for (int i = 0; i < n; ++i) s.changed[i] = 0.0;
  const double* const none = nullptr;
  constexpr int kM = Conserved::kMass, kMX = Conserved::kMomentumX, kMY = Conserved::kMomentumY,
                kE = Conserved::kEnergy;
  const double* source[Conserved::kCount] = {r.source[kM], r.source[kMX], r.source[kMY],
                                             r.source[kE]};
  if (r.gravity_x != 0.0 || r.gravity_y != 0.0) {
    // Gravity: a rho g in the momenta, a rho g.u in the energy, from this stage's input
    // state (read before the passes below overwrite it).
    body_force_pass(r.source, r.U, r.gravity_x, r.gravity_y, s.rhs, n);
    for (int k : {kMX, kMY, kE}) source[k] = s.rhs[k];
  }
  variable_pass<0>(r.fx[kM], r.fy_below[kM], r.fy_above[kM], source[kM], r.inv_dx, r.inv_dy, none,
                   none, none, none, none, none, r.U0[kM], r.U[kM], s.changed, dt, c_new, n);
  variable_pass<1>(r.fx[kMX], r.fy_below[kMX], r.fy_above[kMX], source[kMX], r.inv_dx, r.inv_dy,
                   r.fx_pressure, r.fx_pressure + 1, r.alpha - 1, r.alpha, r.alpha + 1, r.prim.p,
                   r.U0[kMX], r.U[kMX], s.changed, dt, c_new, n);
  variable_pass<2>(r.fx[kMY], r.fy_below[kMY], r.fy_above[kMY], source[kMY], r.inv_dx, r.inv_dy,
                   r.fy_pressure_below, r.fy_pressure_above, r.alpha_below, r.alpha, r.alpha_above,
                   r.prim.p, r.U0[kMY], r.U[kMY], s.changed, dt, c_new, n);
  variable_pass<0>(r.fx[kE], r.fy_below[kE], r.fy_above[kE], source[kE], r.inv_dx, r.inv_dy, none,
                   none, none, none, none, none, r.U0[kE], r.U[kE], s.changed, dt, c_new, n);
  return new_primitives(th, r.U, r.alpha, r.gas_constant, r.prim, s, n);
}

template <class Thermo>
int primitives_row(const Thermo& th, const PrimitiveRow& r, const StageScratch& s) {
  const int n = r.n;
  if (n <= 0) return -1;
  return new_primitives(th, r.U, r.alpha, r.gas_constant, r.prim, s, n);
}

template int stage_update_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&, const StageRow&,
                                                     const StageScratch&, double, double);
template int stage_update_row<ThermallyPerfectAir>(const ThermallyPerfectAir&, const StageRow&,
                                                   const StageScratch&, double, double);
template int primitives_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&,
                                                   const PrimitiveRow&, const StageScratch&);
template int primitives_row<ThermallyPerfectAir>(const ThermallyPerfectAir&, const PrimitiveRow&,
                                                 const StageScratch&);

}  // namespace dustlift
