#include "solver/gas/viscous_rows.hpp"

namespace dustlift {

void viscous_x_faces(const ViscousFaceCells& c, const double* __restrict inv_normal, double inv_tangential,
                     double* __restrict f_mx, double* __restrict f_my, double* __restrict f_e, int n) {
  const double* __restrict ul = c.u_lo;
  const double* __restrict uh = c.u_hi;
  const double* __restrict vl = c.v_lo;
  const double* __restrict vh = c.v_hi;
  const double* __restrict tl = c.T_lo;
  const double* __restrict th = c.T_hi;
  const double* __restrict ml = c.mu_lo;
  const double* __restrict mh = c.mu_hi;
  const double* __restrict kl = c.lambda_lo;
  const double* __restrict kh = c.lambda_hi;
  const double* __restrict al = c.alpha_lo;
  const double* __restrict ah = c.alpha_hi;
  const double* __restrict ulm = c.u_lo_minus;
  const double* __restrict ulp = c.u_lo_plus;
  const double* __restrict uhm = c.u_hi_minus;
  const double* __restrict uhp = c.u_hi_plus;
  const double* __restrict vlm = c.v_lo_minus;
  const double* __restrict vlp = c.v_lo_plus;
  const double* __restrict vhm = c.v_hi_minus;
  const double* __restrict vhp = c.v_hi_plus;
  for (int k = 0; k < n; ++k) {
    const double idn = inv_normal[k];
    const double ux = (uh[k] - ul[k]) * idn;
    const double vx = (vh[k] - vl[k]) * idn;
    const double tx = (th[k] - tl[k]) * idn;
    const double uy = 0.5 * inv_tangential * (uhp[k] - uhm[k] + ulp[k] - ulm[k]);
    const double vy = 0.5 * inv_tangential * (vhp[k] - vhm[k] + vlp[k] - vlm[k]);
    const double mf = 0.5 * (mh[k] + ml[k]);
    const double kf = 0.5 * (kh[k] + kl[k]);
    const double uf = 0.5 * (uh[k] + ul[k]);
    const double vf = 0.5 * (vh[k] + vl[k]);
    const double txx = mf * (4.0 / 3.0 * ux - 2.0 / 3.0 * vy);
    const double txy = mf * (uy + vx);
    const double af = 0.5 * (ah[k] + al[k]);
    f_mx[k] -= af * txx;
    f_my[k] -= af * txy;
    f_e[k] -= af * (uf * txx + vf * txy + kf * tx);
  }
}

void viscous_y_faces(const ViscousFaceCells& c, double inv_normal, const double* __restrict inv_tangential,
                     double* __restrict f_mx, double* __restrict f_my, double* __restrict f_e, int n) {
  const double* __restrict ul = c.u_lo;
  const double* __restrict uh = c.u_hi;
  const double* __restrict vl = c.v_lo;
  const double* __restrict vh = c.v_hi;
  const double* __restrict tl = c.T_lo;
  const double* __restrict th = c.T_hi;
  const double* __restrict ml = c.mu_lo;
  const double* __restrict mh = c.mu_hi;
  const double* __restrict kl = c.lambda_lo;
  const double* __restrict kh = c.lambda_hi;
  const double* __restrict al = c.alpha_lo;
  const double* __restrict ah = c.alpha_hi;
  const double* __restrict ulm = c.u_lo_minus;
  const double* __restrict ulp = c.u_lo_plus;
  const double* __restrict uhm = c.u_hi_minus;
  const double* __restrict uhp = c.u_hi_plus;
  const double* __restrict vlm = c.v_lo_minus;
  const double* __restrict vlp = c.v_lo_plus;
  const double* __restrict vhm = c.v_hi_minus;
  const double* __restrict vhp = c.v_hi_plus;
  for (int k = 0; k < n; ++k) {
    const double it = inv_tangential[k];
    const double uy = (uh[k] - ul[k]) * inv_normal;
    const double vy = (vh[k] - vl[k]) * inv_normal;
    const double ty = (th[k] - tl[k]) * inv_normal;
    const double ux = 0.5 * it * (uhp[k] - uhm[k] + ulp[k] - ulm[k]);
    const double vx = 0.5 * it * (vhp[k] - vhm[k] + vlp[k] - vlm[k]);
    const double mf = 0.5 * (mh[k] + ml[k]);
    const double kf = 0.5 * (kh[k] + kl[k]);
    const double uf = 0.5 * (uh[k] + ul[k]);
    const double vf = 0.5 * (vh[k] + vl[k]);
    const double tyy = mf * (4.0 / 3.0 * vy - 2.0 / 3.0 * ux);
    const double txy = mf * (uy + vx);
    const double af = 0.5 * (ah[k] + al[k]);
    f_mx[k] -= af * txy;
    f_my[k] -= af * tyy;
    f_e[k] -= af * (uf * txy + vf * tyy + kf * ty);
  }
}

}  // namespace dustlift
