#pragma once
// Second-order central viscous and heat fluxes (paper Sect. 2.3; Newtonian stress with
// Stokes' hypothesis, Fourier conduction), porosity-weighted like the convective fluxes and
// subtracted from them, for one row segment of faces. Plain pointer kernels in their own
// file so that the compiler vectorises them (gas_solver.cpp calls them per row).
#include <cstddef>

namespace dustlift {

/// The cells on the two sides of each face of the segment (`lo`: the cell before it, `hi`:
/// after), the cells one row/column to either side across the face direction (`lo_minus`,
/// `lo_plus`, `hi_minus`, `hi_plus`: for the tangential derivatives), per variable.
struct ViscousFaceCells {
  const double *u_lo, *u_hi, *v_lo, *v_hi, *T_lo, *T_hi;
  const double *mu_lo, *mu_hi, *lambda_lo, *lambda_hi, *alpha_lo, *alpha_hi;
  const double *u_lo_minus, *u_lo_plus, *u_hi_minus, *u_hi_plus;
  const double *v_lo_minus, *v_lo_plus, *v_hi_minus, *v_hi_plus;
};

/// Normal direction x (x-faces; normal derivative 1/(x_c - x_{c-1}) per face `inv_normal[k]`,
/// tangential 1/(y_{j+1} - y_{j-1}) constant) or y (y-faces; normal constant, tangential per
/// face). The momentum fluxes along the face normal and tangent and the energy flux get
/// -alpha_f (tau . n) and -alpha_f (u . tau . n + lambda dT/dn).
void viscous_x_faces(const ViscousFaceCells& c, const double* inv_normal, double inv_tangential, double* f_mx,
                     double* f_my, double* f_e, int n);
void viscous_y_faces(const ViscousFaceCells& c, double inv_normal, const double* inv_tangential, double* f_mx,
                     double* f_my, double* f_e, int n);

}  // namespace dustlift
