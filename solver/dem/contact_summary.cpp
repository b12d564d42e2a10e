// The contact laws in words (contact_summary.hpp).
#include "solver/dem/contact_summary.hpp"

#include <cmath>
#include <sstream>

#include "solver/dem/coarse_graining.hpp"
#include "solver/laws/cohesion.hpp"
#include "solver/laws/contact.hpp"

namespace dustlift {
namespace {

double particle_mass(const DemConfig& cfg, double d) { return cfg.density * sphere_volume(d); }

/// The gravity a Bond number is taken with: the scene's, else the standard 9.81 m/s^2.
double bond_gravity(const DemConfig& cfg) {
  const double g = std::hypot(cfg.gravity_x, cfg.gravity_y);
  return g > 0.0 ? g : 9.81;
}

}  // namespace

std::string describe_contact_law(const DemConfig& cfg) {
  const ContactParams& c = cfg.contact;
  std::ostringstream s;
  s << "k_n " << c.k_n << " N/m, k_t " << c.k_t << " N/m";
  if (c.restitution > 0.0) {
    s << ": restitution " << c.restitution
      << " for every pair, the dashpot following each pair's reduced mass";
    if (cfg.wall_contact.restitution > 0.0)
      s << " (at the walls " << cfg.wall_contact.restitution << ", from each particle's mass)";
    return s.str();
  }
  const double d = cfg.particle_diameter;
  s << ", h " << c.damping << " N s/m: restitution "
    << contact_restitution(0.5 * particle_mass(cfg, d), c.k_n, c.damping)
    << " between two particles of " << d * 1e6 << " um";
  if (cfg.size_classes.size() > 1) {
    // One dashpot for every size: the restitution differs between the classes.
    const double lo = cfg.size_classes.front().diameter, hi = cfg.size_classes.back().diameter;
    const auto e = [&](double dk) {
      const double m_eff = 0.5 * particle_mass(cfg, dk);
      const double zeta = contact_damping_ratio(m_eff, c.k_n, c.damping);
      return zeta < 1.0 ? contact_restitution(m_eff, c.k_n, c.damping) : 0.0;
    };
    s << ", " << e(lo) << " between two of " << lo * 1e6 << " um and " << e(hi)
      << " between two of " << hi * 1e6 << " um (one dashpot for every size; a restitution "
      << "instead gives every pair the same)";
  }
  return s.str();
}

std::string describe_cohesion(const DemConfig& cfg) {
  const CohesionParams& c = cfg.cohesion;
  const CohesionParams& w = cfg.wall_cohesion;
  if (!c.enabled() && !w.enabled()) return {};
  const double d = cfg.particle_diameter;
  const double m = particle_mass(cfg, d), g = bond_gravity(cfg);
  const double pair = pull_off_force(c, reduced_radius(0.5 * d, 0.5 * d));
  const double wall = pull_off_force(w, 0.5 * d);
  std::ostringstream s;
  s.precision(4);
  s << "cohesion: van der Waals per real pair (Hamaker " << c.hamaker << " J, wall "
    << w.hamaker << " J; contact separation " << c.min_separation * 1e9 << " nm; ";
  if (c.asperity_radius > 0.0)
    s << "asperities of " << c.asperity_radius * 1e6 << " um (Rumpf); ";
  else
    s << "smooth spheres; ";
  if (c.cutoff > 0.0)
    s << "held at contact, Hamaker tail to a gap of " << c.cutoff * 1e6 << " um)";
  else
    s << "held while the parcels touch)";
  s << ": pull-off force " << pair << " N between two particles of " << d * 1e6
    << " um (Bond number F_c/(m g) " << bond_number(pair, m, g) << " at g = " << g
    << " m/s^2), " << wall << " N at a wall (Bond number " << bond_number(wall, m, g)
    << "); a parcel's total is its real count times these (docs/dem.md, \"Coarse graining\")";
  return s.str();
}

}  // namespace dustlift
