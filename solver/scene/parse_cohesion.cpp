// [particles.cohesion]: van der Waals cohesion between the real particles and with the walls
// (solver/laws/cohesion.hpp, docs/dem.md "Cohesion"). Off without the table, as in the paper.
#include <fmt/format.h>

#include <optional>

#include "solver/laws/cohesion.hpp"
#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {
namespace {

/// The strength of one surface pair, as a Hamaker constant (J) from `hamaker_key` or from a
/// surface energy (J/m^2) at `surface_key`; `fallback` when neither is given.
double read_hamaker(TableReader& t, const char* hamaker_key, const char* surface_key, double s0,
                    double fallback, const std::string& fallback_from) {
  const bool both = t.has(hamaker_key) && t.has(surface_key);
  const std::optional<double> gamma = t.optional_number(surface_key, Range::non_negative());
  if (both)
    t.fail(surface_key, fmt::format("give either {} (J) or {} (J/m^2), not both", hamaker_key,
                                    surface_key));
  if (gamma) return hamaker_of_surface_energy(*gamma, s0);
  if (fallback_from.empty()) return t.number(hamaker_key, fallback, Range::non_negative());
  return t.derived_number(hamaker_key, fallback, fallback_from, Range::non_negative());
}

}  // namespace

void parse_cohesion(TableReader t, DemConfig& dem) {
  if (!t.present()) return;  // no cohesion: nothing read, nothing written
  t.expect_keys({"hamaker", "surface_energy", "min_separation", "asperity_radius", "cutoff",
                 "wall_hamaker", "wall_surface_energy"});
  CohesionParams c;
  c.min_separation = t.number("min_separation", c.min_separation, Range::positive());
  c.hamaker = read_hamaker(t, "hamaker", "surface_energy", c.min_separation, 0.0, "");
  if (KeyFact* f = t.recorded_fact("hamaker")) f->fallback = "0 (no cohesion)";
  if (KeyFact* f = t.recorded_fact("surface_energy")) f->fallback = "optional (instead of hamaker)";
  c.asperity_radius = t.number("asperity_radius", c.asperity_radius, Range::non_negative());
  c.cutoff = t.number("cutoff", c.cutoff,
                      Range::closed(0.0, dem.parcel_diameter).named("in [0, particles.parcel_diameter]"));
  CohesionParams w = c;
  w.hamaker = read_hamaker(t, "wall_hamaker", "wall_surface_energy", c.min_separation, c.hamaker,
                           t.has("surface_energy") ? "particles.cohesion.surface_energy"
                                                   : "particles.cohesion.hamaker");
  if (KeyFact* f = t.recorded_fact("wall_surface_energy"))
    f->fallback = "optional (instead of wall_hamaker)";
  t.finish();
  dem.cohesion = c;
  dem.wall_cohesion = w;
}

}  // namespace dustlift::scene_detail
