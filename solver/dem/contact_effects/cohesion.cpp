// Van der Waals cohesion's line for `dustlift info` and the run log (cohesion.hpp).
#include "solver/dem/contact_effects/cohesion.hpp"

#include <sstream>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/contact_summary.hpp"

namespace dustlift {

std::string CohesionContact::description(const DemConfig& cfg) {
  const CohesionParams& c = cfg.cohesion;
  const CohesionParams& w = cfg.wall_cohesion;
  const double d = cfg.particle_diameter;
  const double m = cfg.density * sphere_volume(d), g = bond_gravity(cfg);
  const double pair = pull_off_force(c, reduced_radius(0.5 * d, 0.5 * d));
  const double wall = pull_off_force(w, 0.5 * d);
  std::ostringstream s;
  s.precision(4);
  s << "cohesion: van der Waals per real pair (Hamaker " << c.hamaker << " J, wall " << w.hamaker
    << " J; contact separation " << c.min_separation * 1e9 << " nm; ";
  if (c.asperity_radius > 0.0)
    s << "asperities of " << c.asperity_radius * 1e6 << " um (Rumpf); ";
  else
    s << "smooth spheres; ";
  if (c.cutoff > 0.0)
    s << "held at contact, Hamaker tail to a gap of " << c.cutoff * 1e6 << " um)";
  else
    s << "held while the parcels touch)";
  s << ": pull-off force " << pair << " N between two particles of " << d * 1e6
    << " um (Bond number F_c/(m g) " << bond_number(pair, m, g) << " at g = " << g << " m/s^2), "
    << wall << " N at a wall (Bond number " << bond_number(wall, m, g)
    << "); a parcel's total is its real count times these (docs/dem.md, \"Coarse graining\")";
  return s.str();
}

}  // namespace dustlift
