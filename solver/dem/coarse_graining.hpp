#pragma once
// Coarse graining of the paper's 2-D variant of Sakai's method (eq. 11;
// docs/dem.md). A parcel of diameter n_xy d is a cylinder of unit depth that
// stands for n_i = n_xy^2 n_z real spheres of diameter d per metre of depth. Pure functions.
#include <numbers>

namespace dustlift {

/// Volume of one real (spherical) particle, m^3.
inline double sphere_volume(double d) { return std::numbers::pi * d * d * d / 6.0; }

/// Area of one parcel's disc in the 2-D plane, m^2.
inline double disc_area(double parcel_d) { return 0.25 * std::numbers::pi * parcel_d * parcel_d; }

/// n_xy = parcel diameter / real particle diameter (eq. 11).
inline double coarse_factor_xy(double parcel_d, double particle_d) { return parcel_d / particle_d; }

/// Real particles per parcel per metre of depth such that n_parcels parcels in a layer of
/// area `area` (m^2 in the x-y plane) hold a 3-D solid volume fraction alpha_p:
/// n = alpha_p area / (n_parcels V_p). For the paper (0.59, 400 mm x 2 mm, 60,000 parcels of
/// 100 um) this is 15,024 per metre, not the paper's printed 90,000 (see docs/dem.md).
inline double derived_real_per_parcel(double alpha_p, double area, double n_parcels, double particle_d) {
  return alpha_p * area / (n_parcels * sphere_volume(particle_d));
}

/// 3-D solid volume fraction of n_parcels parcels holding n_real real particles each
/// (per metre of depth) in `area`.
inline double volume_fraction_3d(double n_parcels, double n_real, double particle_d, double area) {
  return n_parcels * n_real * sphere_volume(particle_d) / area;
}

/// 2-D areal fraction covered by the parcels' discs.
inline double areal_fraction(double n_parcels, double parcel_d, double area) {
  return n_parcels * disc_area(parcel_d) / area;
}

/// Real particles per parcel per metre that make the 3-D volume fraction equal the discs'
/// areal fraction: a parcel disc of area pi D^2/4 and unit depth filled to the same
/// fraction as the plane, n = (pi D^2 / 4) / V_p = 1.5 n_xy^2 / d (15,000 /m for d = 100 um).
inline double equal_fraction_real_per_parcel(double parcel_d, double particle_d) {
  return disc_area(parcel_d) / sphere_volume(particle_d);
}

}  // namespace dustlift
