// The contact laws and the contact units in words (contact_summary.hpp).
#include "solver/dem/contact_summary.hpp"

#include <cmath>
#include <sstream>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/contact_effects/contact_list.hpp"
#include "solver/laws/contact.hpp"

namespace dustlift {
namespace {

double particle_mass(const DemConfig& cfg, double d) {
  return cfg.density * sphere_volume(d);
}

}  // namespace

double bond_gravity(const DemConfig& cfg) {
  const double g = std::hypot(cfg.gravity_x, cfg.gravity_y);
  return g > 0.0 ? g : 9.81;
}

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

std::vector<std::string> contact_descriptions(const DemConfig& cfg) {
  std::vector<std::string> lines;
  for_each_contact_unit([&]<class U>(const U*) {
    if (U::active(cfg)) lines.push_back(U::description(cfg));
  });
  return lines;
}

std::vector<std::string> contact_unit_names() {
  std::vector<std::string> names;
  for_each_contact_unit([&]<class U>(const U*) { names.emplace_back(U::kName); });
  return names;
}

}  // namespace dustlift
