#include "solver/gas/viscous_rows.hpp"

namespace dustlift {
namespace {

/// One kernel for both face directions: `Normal` is 0 for x-faces (the normal derivative's
/// inverse spacing varies per face, the tangential one is constant), 1 for y-faces (the
/// other way round). The stress components along (normal, tangent) map to (x, y) or (y, x).
template <int Normal>
void viscous_faces(const ViscousFaceCells& c, const double* __restrict inv_n_per_face, double inv_n_const,
                   const double* __restrict inv_t_per_face, double inv_t_const, double* __restrict f_mx,
                   double* __restrict f_my, double* __restrict f_e, int n) {
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
    const double in = Normal == 0 ? inv_n_per_face[k] : inv_n_const;
    const double it = Normal == 0 ? inv_t_const : inv_t_per_face[k];
    // Derivatives across the face (normal) and along it (tangential, central over 2 cells).
    const double un = (uh[k] - ul[k]) * in;
    const double vn = (vh[k] - vl[k]) * in;
    const double tn = (th[k] - tl[k]) * in;
    const double ut = 0.5 * it * (uhp[k] - uhm[k] + ulp[k] - ulm[k]);
    const double vt = 0.5 * it * (vhp[k] - vhm[k] + vlp[k] - vlm[k]);
    const double mf = 0.5 * (mh[k] + ml[k]);
    const double kf = 0.5 * (kh[k] + kl[k]);
    const double uf = 0.5 * (uh[k] + ul[k]);
    const double vf = 0.5 * (vh[k] + vl[k]);
    const double af = 0.5 * (ah[k] + al[k]);
    if constexpr (Normal == 0) {  // x-face: ux = un, uy = ut, vx = vn, vy = vt
      const double txx = mf * (4.0 / 3.0 * un - 2.0 / 3.0 * vt);
      const double txy = mf * (ut + vn);
      f_mx[k] -= af * txx;
      f_my[k] -= af * txy;
      f_e[k] -= af * (uf * txx + vf * txy + kf * tn);
    } else {  // y-face: uy = un, ux = ut, vy = vn, vx = vt
      const double tyy = mf * (4.0 / 3.0 * vn - 2.0 / 3.0 * ut);
      const double txy = mf * (un + vt);
      f_mx[k] -= af * txy;
      f_my[k] -= af * tyy;
      f_e[k] -= af * (uf * txy + vf * tyy + kf * tn);
    }
  }
}

}  // namespace

void viscous_x_faces(const ViscousFaceCells& c, const double* inv_normal, double inv_tangential, double* f_mx,
                     double* f_my, double* f_e, int n) {
  viscous_faces<0>(c, inv_normal, 0.0, nullptr, inv_tangential, f_mx, f_my, f_e, n);
}

void viscous_y_faces(const ViscousFaceCells& c, double inv_normal, const double* inv_tangential, double* f_mx,
                     double* f_my, double* f_e, int n) {
  viscous_faces<1>(c, nullptr, inv_normal, inv_tangential, 0.0, f_mx, f_my, f_e, n);
}

}  // namespace dustlift
