#pragma once
// Van der Waals cohesion between real particles, held at its contact value while they touch
// (docs/dem.md, "Cohesion"). Pure functions: the DEM's contact pass, `dustlift info` and the
// tests call these.
//
// Hamaker's sphere-sphere force at a surface gap s, A R*/(6 s^2) (Hamaker 1937, Physica
// 4:1058), with Rumpf's hemispherical asperity of radius a on the surface (Rumpf, Particle
// Technology, 1990): the asperity touches the partner at the gap s and the bodies stand at
// s + a apart,
//   F(s) = (A R* / 6) [ a / ((a + R*) s^2) + 1 / (s + a)^2 ],     s >= s0,
// which is A R*/(6 s^2) for smooth spheres (a = 0). At contact (s <= s0, any overlap) the force
// is held at F(s0): the pull-off force F_c = A R*/(6 s0^2) = 2 pi W R* of smooth spheres with
// W = A/(12 pi s0^2) = 2 gamma, the DMT pull-off (Derjaguin, Muller & Toporov 1975). MFIX's
// DEM applies the same contact-saturated law (its VDW_INNER_CUTOFF).
#include <numbers>

namespace dustlift {

/// The van der Waals law between two surfaces, per pair of REAL particles.
struct CohesionParams {
  double hamaker = 0.0;          ///< J, A; 0: no cohesion
  double min_separation = 4e-10; ///< m, s0: the gap of surfaces in contact
  double asperity_radius = 0.0;  ///< m, a: Rumpf's asperity (0: smooth spheres)
  /// m, the largest surface gap with a force (0: only while the parcels overlap).
  double cutoff = 0.0;
  bool enabled() const { return hamaker > 0.0; }
};

/// R* = r_i r_j / (r_i + r_j) of two spheres (the real particles' radii).
inline double reduced_radius(double r_i, double r_j) { return r_i * r_j / (r_i + r_j); }

/// The Hamaker constant that gives surface energy gamma (J/m^2 per surface) at the contact
/// separation s0: A = 24 pi gamma s0^2 (W = 2 gamma = A / (12 pi s0^2)).
inline double hamaker_of_surface_energy(double gamma, double s0) {
  return 24.0 * std::numbers::pi * gamma * s0 * s0;
}

/// Surface energy per surface of a Hamaker constant: gamma = A / (24 pi s0^2).
inline double surface_energy_of_hamaker(double hamaker, double s0) {
  return hamaker / (24.0 * std::numbers::pi * s0 * s0);
}

/// The attraction (N, > 0) between two real particles of reduced radius R* whose surfaces
/// are `gap` apart: F(max(gap, s0)) of the law above; 0 beyond the cut-off (a gap above
/// 0 with cutoff 0 has none). Wall: R* = the particle's radius (a sphere and a plane).
inline double van_der_waals_force(const CohesionParams& c, double r_star, double gap) {
  if (gap > 0.0 && gap >= c.cutoff) return 0.0;
  const double s = gap > c.min_separation ? gap : c.min_separation;
  const double a = c.asperity_radius;
  if (a == 0.0) return c.hamaker * r_star / (6.0 * s * s);
  const double body = 1.0 / ((s + a) * (s + a));
  return c.hamaker * r_star / 6.0 * (a / ((a + r_star) * s * s) + body);
}

/// The pull-off force F_c (N) of two real particles of reduced radius R* in contact: the
/// force the law holds while they touch, and the pull that separates them quasi-statically.
inline double pull_off_force(const CohesionParams& c, double r_star) {
  return van_der_waals_force(c, r_star, 0.0);
}

/// The overlap at which a linear spring k_n balances a pull-off force F_c: a pair at rest
/// under no other load sits at delta = F_c / k_n.
inline double resting_overlap(double pull_off, double k_n) { return pull_off / k_n; }

/// Bond number F_c / (m g): the cohesion against one particle's weight.
inline double bond_number(double pull_off, double particle_mass, double g) {
  return pull_off / (particle_mass * g);
}

}  // namespace dustlift
