#pragma once
// Van der Waals cohesion between real particles as a contact unit (contact_unit.hpp): its law
// is solver/laws/cohesion.hpp (Hamaker 1937 with Rumpf's asperity, held at the DMT pull-off
// force while the parcels touch), per real pair and between a particle and a wall.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "solver/dem/contact_effects/contact_unit.hpp"
#include "solver/dem/dem_config.hpp"
#include "solver/laws/cohesion.hpp"

namespace dustlift {

class CohesionContact final {
 public:
  static constexpr int kPosition = 10;
  static constexpr const char* kName = "cohesion";
  /// [particles.cohesion] sets a Hamaker constant (for the pairs, the walls or both).
  static bool active(const DemConfig& c) {
    return c.cohesion.enabled() || c.wall_cohesion.enabled();
  }
  /// Its cut-off: the Hamaker tail's reach across a gap.
  static double pair_reach(const DemConfig& c) {
    return c.cohesion.enabled() ? c.cohesion.cutoff : 0.0;
  }
  static double wall_reach(const DemConfig& c) {
    return c.wall_cohesion.enabled() ? c.wall_cohesion.cutoff : 0.0;
  }
  /// "cohesion: van der Waals (...): pull-off force ... (Bond number ...)".
  static std::string description(const DemConfig& c);

  explicit CohesionContact(const DemConfig& c)
      : pair_(c.cohesion),
        wall_(c.wall_cohesion),
        pair_on_(c.cohesion.enabled()),
        wall_on_(c.wall_cohesion.enabled()),
        pair_reach_(pair_reach(c)),
        wall_reach_(wall_reach(c)) {}

  /// The van der Waals tail across the gap of a pair (centres sqrt(d2) apart, radii summing
  /// to rs), up to the cut-off.
  [[gnu::always_inline]] inline bool pair_gap(const ContactColumns& c, std::size_t i,
                                              std::int32_t j, double d2, double rs, double& f,
                                              double& dist) const {
    const double reach = rs + pair_reach_;
    if (!(pair_on_ && pair_reach_ > 0.0 && d2 < reach * reach)) return false;
    dist = std::sqrt(d2);
    f = van_der_waals_force(pair_, r_star(c, i, j), dist - rs);
    return true;
  }
  /// While the pair touches: the pull-off force (the Coulomb limit saw the spring-dashpot load,
  /// which holds the adhesion: DMT).
  [[gnu::always_inline]] inline bool pair_touching(const ContactColumns& c, std::size_t i,
                                                   std::int32_t j, double& f) const {
    if (!pair_on_) return false;
    f = pull_off_force(pair_, r_star(c, i, j));
    return true;
  }
  /// A sphere and a plane `gap` apart (R* = the real particle's radius).
  [[gnu::always_inline]] inline bool wall_gap(const ContactColumns& c, std::size_t i, double gap,
                                              double& f) const {
    if (!(wall_on_ && gap < wall_reach_)) return false;
    f = van_der_waals_force(wall_, 0.5 * c.real_diameter[i], gap);
    return true;
  }
  [[gnu::always_inline]] inline bool wall_touching(const ContactColumns& c, std::size_t i,
                                                   double& f) const {
    if (!wall_on_) return false;
    f = pull_off_force(wall_, 0.5 * c.real_diameter[i]);
    return true;
  }
  /// The work of the force held over the overlap, for `weight` real contacts (its tail across
  /// a gap is left out).
  void pair_energy(const ContactColumns& c, std::size_t i, std::int32_t j, double overlap,
                   double weight, double& e) const {
    if (pair_on_) e -= weight * pull_off_force(pair_, r_star(c, i, j)) * overlap;
  }
  void wall_energy(const ContactColumns& c, std::size_t i, double overlap, double weight,
                   double& e) const {
    if (wall_on_) e -= weight * pull_off_force(wall_, 0.5 * c.real_diameter[i]) * overlap;
  }

 private:
  [[gnu::always_inline]] static inline double r_star(const ContactColumns& c, std::size_t i,
                                                     std::int32_t j) {
    return reduced_radius(0.5 * c.real_diameter[i], 0.5 * c.real_diameter[j]);
  }

  CohesionParams pair_, wall_;
  bool pair_on_, wall_on_;
  double pair_reach_, wall_reach_;
};

}  // namespace dustlift
