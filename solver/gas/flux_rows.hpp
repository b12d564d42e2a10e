#pragma once
// Inviscid face fluxes of one row of faces (an x-row or a y-row), computed in passes over
// contiguous arrays so that the compiler vectorises them: MUSCL reconstruction of
// (rho, u, v, p) into scratch rows, the positivity fallback, then SLAU2 times the face porosity.
// Face f of the row lies between stencil cells m1[f] and c0[f]; m2[f] and p1[f] are the
// outer stencil cells (for an x-row the arrays are the row shifted by one cell each, for a
// y-row they are four consecutive grid rows).
#include "solver/gas/muscl.hpp"
#include "solver/gas/thermo.hpp"

namespace dustlift {

/// One primitive variable's four-cell stencil along a row of faces.
struct StencilRows {
  const double* m2;
  const double* m1;
  const double* c0;
  const double* p1;
};

struct FaceRowInput {
  StencilRows rho, u, v, p;
  const double* alpha_m1;  ///< porosity of the cell before each face
  const double* alpha_c0;  ///< porosity of the cell after each face
  int faces;
};

/// Scratch: 8 arrays of at least `faces` doubles (left/right rho, u, v, p).
struct FaceRowScratch {
  double* rho_l;
  double* u_l;
  double* v_l;
  double* p_l;
  double* rho_r;
  double* u_r;
  double* v_r;
  double* p_r;
};

/// Output per face: porosity-weighted fluxes of mass, convective x/y momentum and energy,
/// and the face pressure p~ (not weighted; the full momentum flux is the convective part plus
/// alpha_face p~ n, see slau2_split_flux).
struct FaceRowOutput {
  double* mass;
  double* momentum_x;
  double* momentum_y;
  double* energy;
  double* pressure;
};

/// Fills `out` for one row of faces with unit normal (nx, ny), `in.faces` faces from the
/// stencil pointers on (a sub-range of a row is the same call with shifted pointers).
template <class Thermo>
void inviscid_flux_row(const Thermo& thermo, const MusclSettings& muscl, const FaceRowInput& in,
                       const FaceRowScratch& scratch, const FaceRowOutput& out, double nx, double ny);

extern template void inviscid_flux_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&, const MusclSettings&,
                                                              const FaceRowInput&, const FaceRowScratch&,
                                                              const FaceRowOutput&, double, double);
extern template void inviscid_flux_row<ThermallyPerfectAir>(const ThermallyPerfectAir&, const MusclSettings&,
                                                            const FaceRowInput&, const FaceRowScratch&,
                                                            const FaceRowOutput&, double, double);

}  // namespace dustlift
