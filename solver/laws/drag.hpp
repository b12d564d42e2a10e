#pragma once
// Drag laws (Table 1 and the dense-suspension closures): the force on one real particle is
// F = beta u_r, u_r the slip (gas minus particle velocity), with beta from the standard curve
// of Clift & Gauvin, Parmar's compressibility factor xi_1(M, Re) and a volume-fraction
// closure. Garbled print forms in the paper are corrected as docs/coupling.md explains.
#include "solver/core/vec2.hpp"

namespace dustlift::aero {

/// Standard drag curve, Clift & Gauvin (1970); docs/coupling.md (the paper's print lacks
/// the 0.687 exponent and multiplies where it should divide).
double cd_standard(double re);
/// Re * C_D,std: finite as Re -> 0 (Stokes limit 24).
double re_cd_standard(double re);

/// Parmar, Haselbacher & Balachandar (2010) compressible drag C_D(M, Re); M > 1.75 holds the
/// M = 1.75 fit (not fitted beyond).
double cd_parmar(double mach, double re);
double re_cd_parmar(double mach, double re);
/// xi_1(M, Re) = C_D(M, Re) / C_D,std(Re).
double xi1_parmar(double mach, double re);

/// The drag closure for a particle among others: a volume-fraction factor xi_2(alpha_g) on the
/// isolated sphere's drag (Sangani, linear, none), or a closure of dense suspensions as a whole
/// (Tenneti, Osnes: dense_drag.hpp).
struct VolumeFractionCorrection {
  enum class Kind { None, Sangani, Linear, Tenneti, Osnes };
  Kind kind = Kind::Sangani;
  /// phi = alpha_p is capped at this value before evaluation (1 = no cap).
  double phi_cap = 1.0;
};
/// Sangani, Zhang & Prosperetti (1991) as used by Ling et al. (2012):
/// xi_2 = (1 + 2 phi) / (1 - phi)^3; Linear: 1 + 5.94 phi; None, Tenneti, Osnes: 1.
double xi2(double alpha_g, const VolumeFractionCorrection& c);

/// Local gas state interpolated to a parcel (eq. 16).
struct GasAtParcel {
  double rho = 1.0;    ///< kg/m^3 (gas density, not alpha_g rho)
  Vec2 u{};            ///< m/s
  double mu = 1.8e-5;  ///< Pa s
  double c = 340.0;    ///< m/s
  double alpha_g = 1.0;
  double gamma = 1.4;  ///< ratio of specific heats (Osnes's Knudsen number)
};

/// Drag per unit slip speed of one real particle, beta in F_drag = beta u_r (Table 1):
/// beta = 3 pi mu d (Re C_D / 24) xi_2(alpha_g), C_D with Parmar's xi_1(M, Re) when
/// `compressible`, else the Clift-Gauvin curve; finite at zero slip (Stokes). The Tenneti and
/// Osnes closures give beta as published (dense_drag.hpp; Tenneti is incompressible, Osnes has
/// its own Mach-number dependence: `compressible` does not apply to them).
double drag_coefficient(const GasAtParcel& g, double slip, double d, bool compressible,
                        const VolumeFractionCorrection& c);

/// The drag at the slip u_r for a drag coefficient beta: F = beta u_r (what a DEM sub-step
/// applies with the beta of the CFD step's start).
inline Vec2 linear_drag(double beta, Vec2 u_r) {
  return {beta * u_r.x, beta * u_r.y};
}

/// Drag on one real particle of diameter d moving with velocity up (Table 1):
/// F = 3 pi mu d u_r (Re/24) C_D,std xi_1 xi_2, u_r = u_g - u_p.
Vec2 drag_force(const GasAtParcel& g, Vec2 up, double d, const VolumeFractionCorrection& c);

}  // namespace dustlift::aero
