#pragma once
// What the scene's contact laws mean for its particles, in words for `dustlift info` and the
// run log: the restitution pairs get, and the cohesion's pull-off force and Bond number.
#include <string>

#include "solver/dem/dem_config.hpp"

namespace dustlift {

/// The contact law's part of the particles line: "k_n ..., k_t ..., h ...: restitution ...".
std::string describe_contact_law(const DemConfig& cfg);

/// "cohesion: van der Waals (...): pull-off force ... (Bond number ...)"; "" when off.
std::string describe_cohesion(const DemConfig& cfg);

}  // namespace dustlift
