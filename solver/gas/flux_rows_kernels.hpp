#pragma once
// Template definitions of the inviscid flux row kernels (flux_rows.hpp). Included by one .cpp
// per thermodynamic model: with both instantiations in one file GCC vectorised only one of
// them. Those .cpp files are compiled with -fno-math-errno -fno-trapping-math (see
// solver/CMakeLists.txt) so that GCC turns the selects of the limiter, SLAU2 and the NASA
// range switch into vector blends and vectorises sqrt; neither option changes a computed value.
#include "solver/gas/flux_rows.hpp"

#include <algorithm>

#include "solver/gas/slau2.hpp"

namespace dustlift {
namespace {

template <Reconstruction Order, Limiter L>
void reconstruct_row(const StencilRows& q, double* left, double* right, int n, double kappa, double b) {
  const double* __restrict m2 = q.m2;
  const double* __restrict m1 = q.m1;
  const double* __restrict c0 = q.c0;
  const double* __restrict p1 = q.p1;
  double* __restrict l = left;
  double* __restrict r = right;
  for (int f = 0; f < n; ++f) {
    if constexpr (Order == Reconstruction::FirstOrder) {
      l[f] = m1[f];
      r[f] = c0[f];
    } else {
      l[f] = muscl_extrapolate<L, +1>(m1[f], m1[f] - m2[f], c0[f] - m1[f], kappa, b);
      r[f] = muscl_extrapolate<L, -1>(c0[f], c0[f] - m1[f], p1[f] - c0[f], kappa, b);
    }
  }
}

/// The same values for a row of faces whose stencil cells are contiguous (x-faces: q[f] is
/// cell f, face f lies between cells f-1 and f): each cell's two limited slopes are computed
/// once and give both its face values, its right face's left state and its left face's
/// right state, instead of twice (muscl_extrapolation_pair: the same operations, so the same
/// bits).
template <Limiter L>
[[gnu::noinline]] void reconstruct_contiguous_row(const double* q, double* left, double* right, int n, double kappa,
                                                  double b) {
  const double* __restrict c = q;
  double* __restrict l = left;
  double* __restrict r = right;
  double plus = 0.0, minus = 0.0;
  // Cell -1 gives only face 0's left state, cell n-1 only face n-1's right state.
  muscl_extrapolation_pair<L>(c[-1], c[-1] - c[-2], c[0] - c[-1], kappa, b, plus, minus);
  l[0] = plus;
  for (int i = 0; i < n - 1; ++i) {
    double pl, mi;
    muscl_extrapolation_pair<L>(c[i], c[i] - c[i - 1], c[i + 1] - c[i], kappa, b, pl, mi);
    l[i + 1] = pl;
    r[i] = mi;
  }
  muscl_extrapolation_pair<L>(c[n - 1], c[n - 1] - c[n - 2], c[n] - c[n - 1], kappa, b, plus, minus);
  r[n - 1] = minus;
}

template <Reconstruction Order, Limiter L>
void reconstruct_variable(const StencilRows& q, double* left, double* right, int n, double kappa, double b) {
  if constexpr (Order != Reconstruction::FirstOrder) {
    if (q.m2 + 1 == q.m1 && q.m1 + 1 == q.c0 && q.c0 + 1 == q.p1) {
      reconstruct_contiguous_row<L>(q.c0, left, right, n, kappa, b);
      return;
    }
  }
  reconstruct_row<Order, L>(q, left, right, n, kappa, b);
}

template <Reconstruction Order, Limiter L>
void reconstruct_all(const FaceRowInput& in, const FaceRowScratch& s, double kappa, double b) {
  reconstruct_variable<Order, L>(in.rho, s.rho_l, s.rho_r, in.faces, kappa, b);
  reconstruct_variable<Order, L>(in.u, s.u_l, s.u_r, in.faces, kappa, b);
  reconstruct_variable<Order, L>(in.v, s.v_l, s.v_r, in.faces, kappa, b);
  reconstruct_variable<Order, L>(in.p, s.p_l, s.p_r, in.faces, kappa, b);
}

/// Positivity safeguard: a face whose reconstructed rho or p is <= 0 on either side falls
/// back to first order (all four variables).
[[gnu::noinline]] void positivity_fallback_loop(double* __restrict rl, double* __restrict ul, double* __restrict vl,
                              double* __restrict pl, double* __restrict rr, double* __restrict ur,
                              double* __restrict vr, double* __restrict pr, const double* __restrict rho_m1,
                              const double* __restrict u_m1, const double* __restrict v_m1,
                              const double* __restrict p_m1, const double* __restrict rho_c0,
                              const double* __restrict u_c0, const double* __restrict v_c0,
                              const double* __restrict p_c0, int n) {
  for (int f = 0; f < n; ++f) {
    const bool bad = std::min(std::min(rl[f], rr[f]), std::min(pl[f], pr[f])) <= 0.0;
    rl[f] = bad ? rho_m1[f] : rl[f];
    ul[f] = bad ? u_m1[f] : ul[f];
    vl[f] = bad ? v_m1[f] : vl[f];
    pl[f] = bad ? p_m1[f] : pl[f];
    rr[f] = bad ? rho_c0[f] : rr[f];
    ur[f] = bad ? u_c0[f] : ur[f];
    vr[f] = bad ? v_c0[f] : vr[f];
    pr[f] = bad ? p_c0[f] : pr[f];
  }
}

/// Positivity safeguard: a face whose reconstructed rho or p is <= 0 on either side falls
/// back to first order (all four variables).
void positivity_fallback(const FaceRowInput& in, const FaceRowScratch& s) {
  positivity_fallback_loop(s.rho_l, s.u_l, s.v_l, s.p_l, s.rho_r, s.u_r, s.v_r, s.p_r, in.rho.m1, in.u.m1, in.v.m1,
                           in.p.m1, in.rho.c0, in.u.c0, in.v.c0, in.p.c0, in.faces);
}

/// Thermodynamics with a cheaper form below some temperature (thermally perfect air: one
/// polynomial range below 1000 K) gives the same values from it.
template <class Thermo>
concept HasLowRange = requires(const Thermo& t, double T, double& h, double& cp) {
  t.enthalpy_and_cp_low(T, h, cp);
  Thermo::low_range_limit();
};

template <bool LowOnly, class Thermo>
inline FaceState face_state(const Thermo& th, double R, double rho, double u, double v, double p) {
  const double T = p / (rho * R);
  double h, cp;
  if constexpr (LowOnly) {
    th.enthalpy_and_cp_low(T, h, cp);
  } else {
    th.enthalpy_and_cp(T, h, cp);
  }
  // c^2 = gamma R T = cp/(cp - R) p/rho.
  return {rho, u, v, p, h + 0.5 * (u * u + v * v), std::sqrt(cp * p / ((cp - R) * rho))};
}

/// SLAU2 times the face porosity for every face of the row (face pressure apart, unweighted). Kept out of line: GCC honours the
/// restrict parameters only then, which lets it hoist the thermo constants and vectorise.
template <bool LowOnly, class Thermo>
[[gnu::noinline]] void flux_loop(const Thermo& th, double R, const double* __restrict rl, const double* __restrict ul,
               const double* __restrict vl, const double* __restrict pl, const double* __restrict rr,
               const double* __restrict ur, const double* __restrict vr, const double* __restrict pr,
               const double* __restrict a_m1, const double* __restrict a_c0, double* __restrict f_mass,
               double* __restrict f_mx, double* __restrict f_my, double* __restrict f_e,
               double* __restrict f_p, int n, double nx, double ny) {
  for (int f = 0; f < n; ++f) {
    const FaceState L = face_state<LowOnly>(th, R, rl[f], ul[f], vl[f], pl[f]);
    const FaceState Rs = face_state<LowOnly>(th, R, rr[f], ur[f], vr[f], pr[f]);
    const SplitFlux F = slau2_split_flux(L, Rs, nx, ny);
    const double a = 0.5 * (a_m1[f] + a_c0[f]);
    f_mass[f] = a * F.mass;
    f_mx[f] = a * F.momentum_x;
    f_my[f] = a * F.momentum_y;
    f_e[f] = a * F.energy;
    f_p[f] = F.pressure;
  }
}

/// Whether every face side has p/(rho R) below t_limit (NaN counts as not below).
[[gnu::noinline, maybe_unused]] bool faces_below_temperature(const FaceRowScratch& s, int n, double R,
                                                             double t_limit) {
  const double* __restrict rl = s.rho_l;
  const double* __restrict rr = s.rho_r;
  const double* __restrict pl = s.p_l;
  const double* __restrict pr = s.p_r;
  const double k = t_limit * R;
  int above = 0;
  for (int f = 0; f < n; ++f) above |= (pl[f] < k * rl[f] && pr[f] < k * rr[f]) ? 0 : 1;
  return above == 0;
}

}  // namespace

template <class Thermo>
void inviscid_flux_row(const Thermo& th, const MusclSettings& m, const FaceRowInput& in, const FaceRowScratch& s,
                       const FaceRowOutput& out, double nx, double ny) {
  using R_ = Reconstruction;
  using L_ = Limiter;
  if (m.order == R_::FirstOrder) {
    reconstruct_all<R_::FirstOrder, L_::Minmod>(in, s, m.kappa, m.b);
  } else if (m.limiter == L_::Minmod) {
    reconstruct_all<R_::Muscl3, L_::Minmod>(in, s, m.kappa, m.b);
  } else {
    reconstruct_all<R_::Muscl3, L_::VanAlbada>(in, s, m.kappa, m.b);
  }
  if (m.order != R_::FirstOrder) positivity_fallback(in, s);

  bool low_only = false;
  if constexpr (HasLowRange<Thermo>) {
    // Every face temperature p/(rho R) below the range break: the low polynomials alone give
    // the same values (the select would pick them) at half the cost.
    low_only = faces_below_temperature(s, in.faces, th.gas_constant(), Thermo::low_range_limit());
  }
  if (low_only) {
    if constexpr (HasLowRange<Thermo>) {
      flux_loop<true>(th, th.gas_constant(), s.rho_l, s.u_l, s.v_l, s.p_l, s.rho_r, s.u_r, s.v_r, s.p_r, in.alpha_m1,
                      in.alpha_c0, out.mass, out.momentum_x, out.momentum_y, out.energy, out.pressure, in.faces, nx,
                      ny);
    }
  } else {
    flux_loop<false>(th, th.gas_constant(), s.rho_l, s.u_l, s.v_l, s.p_l, s.rho_r, s.u_r, s.v_r, s.p_r, in.alpha_m1,
                     in.alpha_c0, out.mass, out.momentum_x, out.momentum_y, out.energy, out.pressure, in.faces, nx,
                     ny);
  }
}

}  // namespace dustlift
