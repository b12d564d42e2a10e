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

/// How the volume-fraction correction xi_2(alpha_g) is evaluated.
struct VolumeFractionCorrection {
  enum class Kind { None, Sangani, Linear, Tenneti };
  Kind kind = Kind::Sangani;
  /// phi = alpha_p is capped at this value before evaluation (1 = no cap).
  double phi_cap = 1.0;
};
/// Sangani, Zhang & Prosperetti (1991) as used by Ling et al. (2012):
/// xi_2 = (1 + 2 phi) / (1 - phi)^3; Linear: 1 + 5.94 phi; None: 1. (Tenneti is not a factor
/// on the isolated drag: see tenneti_drag_factor.)
double xi2(double alpha_g, const VolumeFractionCorrection& c);

/// Tenneti, Garg & Subramaniam (2011, Int. J. Multiphase Flow 37:1072), from particle-resolved
/// simulations of random arrays at 0.1 <= phi <= 0.5, 0.01 <= Re_m <= 300: the drag of one
/// particle per 3 pi mu d u_r, with the mean pressure drag taken out (the pressure-gradient
/// force -V_p grad p is its own effect), as OpenFOAM's Tenneti model and Osnes et al. (2023,
/// Int. J. Multiphase Flow 165:104485) take it:
///   F = (Re_m C_D(Re_m) / 24) / (1 - phi) + (1 - phi) (b1 + b2),  Re_m = (1 - phi) Re,
///   b1 = 5.81 phi / (1 - phi)^2 + 0.48 phi^(1/3) / (1 - phi)^3,
///   b2 = (1 - phi)^2 phi^3 Re (0.95 + 0.61 phi^3 / (1 - phi)^2),
/// with the isolated sphere's Re C_D given at Re_m (`re_cd_isolated`, the scene's curve:
/// Clift-Gauvin, or Parmar's compressible one). Tenneti's own isolated curve is
/// Schiller-Naumann's, 24 (1 + 0.15 Re^0.687), which Clift-Gauvin extends.
double tenneti_drag_factor(double re_cd_isolated, double re, double phi);

/// Local gas state interpolated to a parcel (eq. 16).
struct GasAtParcel {
  double rho = 1.0;    ///< kg/m^3 (gas density, not alpha_g rho)
  Vec2 u{};            ///< m/s
  double mu = 1.8e-5;  ///< Pa s
  double c = 340.0;    ///< m/s
  double alpha_g = 1.0;
};

/// Drag per unit slip speed of one real particle, beta in F_drag = beta u_r (Table 1):
/// beta = 3 pi mu d (Re C_D / 24) xi_2(alpha_g), C_D with Parmar's xi_1(M, Re) when
/// `compressible`, else the Clift-Gauvin curve; finite at zero slip (Stokes).
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
