#pragma once
// Heat transfer (eqs. 7-10, Ranz & Marshall 1952), per real particle:
// Q = pi d^2 (Nu lambda / d) (T_g - T_p) = H (T_g - T_p) with the conductance H = pi d lambda Nu;
// a DEM sub-step applies H of the CFD step's start to the parcel's current temperature.
#include <cmath>
#include <numbers>

namespace dustlift::aero {

/// Ranz & Marshall (1952) Nusselt number: 2 + 0.6 Re^1/2 Pr^1/3 (the paper prints it garbled).
inline double nusselt_ranz_marshall(double re, double pr) {
  return 2.0 + 0.6 * std::sqrt(re) * std::cbrt(pr);
}

/// H = pi d lambda Nu = pi d^2 (Nu lambda / d), W/K.
inline double heat_conductance(double d, double lambda, double nusselt) {
  return std::numbers::pi * d * lambda * nusselt;
}

/// The heat flow into one particle at its temperature for the conductance H: Q = H (T_g - T_p).
inline double linear_heat_flow(double H, double t_gas, double t_particle) {
  return H * (t_gas - t_particle);
}

/// Heat flow into one particle (eqs. 8-9): Q = pi d^2 (Nu lambda / d) (T_g - T_p).
double heat_flow(double lambda, double nusselt, double d, double t_gas, double t_particle);

}  // namespace dustlift::aero
