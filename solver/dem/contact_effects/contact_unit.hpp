#pragma once
// What a contact unit (contact_effects/<name>.hpp, a `class <Name>Contact final`) declares and
// sees. The contact pass composes the active units at compile time (dem_step.cpp): each one's
// forces are inlined where the pass adds them, and a unit that is off runs no code.
//
// A unit has: kPosition (the order the pass adds the units' forces in); kName; `static bool
// active(const DemConfig&)`; a constructor from the DemConfig; `static double
// pair_reach(const DemConfig&)` and `wall_reach` (how far beyond touching it acts; 0: only
// while touching); `static std::string description(const DemConfig&)` (its line for info and
// run.log); and, per real contact, the normal forces (> 0: attraction, along the normal
// towards the partner) it adds across a gap and while touching, and its energy:
//   bool pair_gap(const ContactColumns&, i, j, d2, rs, double& f, double& dist) const;
//   bool pair_touching(const ContactColumns&, i, j, double& f) const;
//   bool wall_gap(const ContactColumns&, i, double gap, double& f) const;
//   bool wall_touching(const ContactColumns&, i, double& f) const;
//   void pair_energy(const ContactColumns&, i, j, double overlap, double weight, double& e) const;
//   void wall_energy(const ContactColumns&, i, double overlap, double weight, double& e) const;
// (each returns false, or leaves e, when the unit adds nothing there).
#include <cstddef>

namespace dustlift {

/// The per-parcel columns a contact unit reads.
struct ContactColumns {
  const double* real_diameter;  ///< m, the diameter of the parcel's real particles
};

}  // namespace dustlift
