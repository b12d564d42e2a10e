#pragma once
// What the scene's contact laws mean for its particles, in words for `dustlift info` and the
// run log: the restitution pairs get, and the lines of the active contact units (e.g. the
// cohesion's pull-off force and Bond number).
#include <string>
#include <vector>

#include "solver/dem/dem_config.hpp"

namespace dustlift {

/// The contact law's part of the particles line: "k_n ..., k_t ..., h ...: restitution ...".
std::string describe_contact_law(const DemConfig& cfg);

/// One line per active contact unit (contact_effects/), in the order the contact pass adds them,
/// e.g. "cohesion: van der Waals (...): pull-off force ... (Bond number ...)"; none when off.
std::vector<std::string> contact_descriptions(const DemConfig& cfg);

/// Every contact unit of the build (its kName), in that order.
std::vector<std::string> contact_unit_names();

/// The gravity a Bond number is taken with: the scene's, else the standard 9.81 m/s^2.
double bond_gravity(const DemConfig& cfg);

}  // namespace dustlift
