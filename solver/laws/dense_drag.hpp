#pragma once
// Drag closures for dense random suspensions, per real particle, as drag coefficients beta in
// F = beta u_r (u_r the interstitial slip, gas minus particle velocity). Both give the drag with
// the mean pressure drag taken out: the pressure-gradient force -V_p grad p is its own effect
// (in a steady homogeneous suspension the particles' share phi of the total drag is that force,
// so the drag is (1 - phi) times the total; docs/coupling.md).
namespace dustlift::aero {

/// Tenneti, Garg & Subramaniam (2011, Int. J. Multiphase Flow 37:1072), fitted to particle-
/// resolved simulations of fixed random arrays at 0.1 <= phi <= 0.5 and Re_m <= 300: the total
/// force per 3 pi mu d (1 - phi) |u_r| is
///   F_T = F_isol(Re_m) / (1 - phi)^3 + F_phi + F_phi,Re,   Re_m = (1 - phi) Re,
///   F_isol = 1 + 0.15 Re_m^0.687 (Schiller-Naumann),
///   F_phi = 5.81 phi / (1 - phi)^3 + 0.48 phi^(1/3) / (1 - phi)^4,
///   F_phi,Re = phi^3 Re_m (0.95 + 0.61 phi^3 / (1 - phi)^2);
/// the drag without the mean pressure drag is (1 - phi) of it. Returns beta / (3 pi mu d) =
/// (1 - phi)^2 F_T; Re = rho |u_r| d / mu.
double tenneti_drag_factor(double re, double phi);

/// Loth, Daspit, Jeong, Nagata & Nonomura (2021, AIAA J. 59:3261): Re C_D / 24 of an isolated
/// sphere at the particle Reynolds number Re, slip Mach number M and Knudsen number Kn (gas
/// ratio of specific heats gamma). Re <= 45: rarefaction-dominated (the continuum curve times
/// the Knudsen factor, blended with the free-molecular drag by M^4); Re > 45: compression-
/// dominated (the standard curve with Mach-dependent coefficients C_M, G_M, H_M).
double re_cd_loth(double re, double mach, double kn, double gamma);

/// Knudsen number of a particle of diameter d in a gas: Kn = sqrt(pi gamma / 2) M / Re =
/// sqrt(pi gamma / 2) mu / (rho c d) (independent of the slip).
double knudsen_number(double rho, double mu, double c, double d, double gamma);

/// Osnes, Vartdal, Khalloufi, Capecelatro & Balachandar (2023, Int. J. Multiphase Flow
/// 165:104485), fitted to particle-resolved simulations of compressible flow through random
/// suspensions (phi up to 0.4, subsonic to weakly supersonic slip):
///   C_D = C_D,Loth(Re, M) / (1 - phi) + b3 + (24 / Re) (1 - phi) (b1 + b2),
///   b1 = 5.81 phi / (1 - phi)^2 + 0.48 phi^(1/3) / (1 - phi)^3,
///   b2 = (1 - phi)^2 phi^3 Re (0.95 + 0.61 phi^3 / (1 - phi)^2),
///   b3 = min(sqrt(20 M), 1) (5.65 phi - 22 phi^2 + 23.4 phi^3)
///        (1 + tanh((M - (0.65 - 0.24 phi)) / 0.35)),
/// with Re and M at the interstitial slip (b1 and b2 are Tenneti's phi terms without the mean
/// pressure drag; b3 the Mach number's effect on a suspension). Returns beta / (3 pi mu d) =
/// Re C_D / 24.
double osnes_drag_factor(double re, double mach, double kn, double gamma, double phi);

/// Ergun (1952)'s packed-bed pressure drop, Delta p / L = 150 mu U phi^2 / ((1 - phi)^3 d^2) +
/// 1.75 rho U^2 phi / ((1 - phi)^3 d) at the superficial velocity U = (1 - phi) |u_r|, as the
/// drag of one particle without the mean pressure drag, beta / (3 pi mu d) =
/// (150 / 18) phi / (1 - phi) + (1.75 / 18) Re: the reference a closure is held against in a
/// packed bed.
double ergun_drag_factor(double re, double phi);

}  // namespace dustlift::aero
