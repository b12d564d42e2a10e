#pragma once
// The average of a field over a sphere's volume, for a particle whose undisturbed flow varies
// across it (the Faxen form of the pressure-gradient and inviscid-unsteady forces: Parmar,
// Haselbacher & Balachandar 2009; Annamalai & Balachandar 2017, J. Fluid Mech. 816:381). In the
// 2-D plane a sphere of radius a weighs each point by its chord 2 sqrt(a^2 - xi^2 - eta^2);
// the rule is Gauss-Legendre across the streamwise diameter (16 points) and Gauss-Chebyshev of
// the second kind along each chord (3 points), exact for polynomials of degree 31 in xi and 5
// in eta. Where the sphere lies inside one interpolation triangle (cells larger than the
// particle, the usual case) the average of the linear interpolant is its centre value.
#include <array>

namespace dustlift {

struct SpherePoint {
  double xi, eta;  ///< offsets from the centre in units of the radius
  double weight;   ///< share of the sphere's volume (the weights sum to 1)
};

inline constexpr int kSpherePoints = 48;

/// The points of the rule.
const std::array<SpherePoint, kSpherePoints>& sphere_points();

}  // namespace dustlift
