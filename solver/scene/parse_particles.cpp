// [particles]: the DEM parcel system (owned by the DEM module). Defaults are the paper's
// (Table 2, physics-reference.md §3.7, §4); choices where the paper is silent or garbled
// are explained in docs/dem.md.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/scene/parcel_file.hpp"
#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {
namespace {

/// [particles.contact] or [particles.wall_contact]; `fallback` gives the defaults.
ContactParams parse_contact(TableReader t, const ContactParams& fallback) {
  ContactParams c;
  c.k_n = t.number("k_n", fallback.k_n, Range::positive());
  c.k_t = t.number("k_t", fallback.k_t, Range::non_negative());
  c.damping = t.number("damping", fallback.damping, Range::non_negative());
  const bool coulomb = t.boolean("coulomb", std::isfinite(fallback.friction));
  if (coulomb) {
    c.friction = t.number("friction", std::isfinite(fallback.friction) ? fallback.friction : 0.5,
                          Range::non_negative());
  } else {
    if (t.has("friction")) t.fail("friction", "only used with coulomb = true");
    c.friction = std::numeric_limits<double>::infinity();
  }
  t.finish();
  return c;
}

LayerArrangement parse_arrangement(TableReader& lt) {
  const std::string name = lt.string("arrangement", "jittered_lattice");
  std::string allowed;
  for (const auto& [known, value] : kLayerArrangementNames) {
    if (known == name) return value;
    allowed += (allowed.empty() ? "\"" : ", \"") + std::string(known) + "\"";
  }
  lt.fail("arrangement", "\"" + name + "\" is not one of " + allowed);
}

}  // namespace

void parse_particles(TableReader t, DemConfig& dem, const GridConfig& grid, const BoundaryConfig& boundary) {
  dem.enabled = t.boolean("enabled", t.present());
  if (!dem.enabled) {
    t.finish();
    return;
  }
  dem.particle_diameter = t.number("diameter", dem.particle_diameter, Range::positive());
  dem.density = t.number("density", dem.density, Range::positive());
  dem.heat_capacity = t.number("heat_capacity", dem.heat_capacity, Range::positive());
  dem.initial_temperature = t.number("temperature", dem.initial_temperature, Range::positive());
  dem.parcel_diameter = t.number("parcel_diameter", dem.particle_diameter, Range::positive());
  if (dem.parcel_diameter < dem.particle_diameter) {
    t.fail("parcel_diameter", "must be at least the particle diameter (n_xy >= 1, eq. 11)");
  }

  TableReader lt = t.table("layer");
  LayerConfig& L = dem.layer;
  L.x_min = lt.number("x_min", L.x_min);
  L.x_max = lt.number("x_max", L.x_max);
  if (!(L.x_max > L.x_min)) lt.fail("x_max", "must be greater than x_min");
  L.y_min = lt.number("y_min", L.y_min);
  L.y_max = lt.number("y_max", L.y_max);
  if (!(L.y_max > L.y_min)) lt.fail("y_max", "must be greater than y_min");
  L.arrangement = parse_arrangement(lt);
  const bool settled = L.arrangement == LayerArrangement::Settled;
  L.settle = lt.boolean("settle", settled || L.settle);
  if (settled && !L.settle) lt.fail("settle", "arrangement = \"settled\" always settles the layer");
  // Real particles per parcel per metre of depth (§4), derived unless the scene sets it:
  // the layer rectangle then holds volume_fraction of solid in 3-D (15,024 /m for the
  // paper's layer). A layer file without volume_fraction fills each parcel's disc to the
  // plane's fraction instead, (pi D^2/4) / V_p (15,000 /m for 100 um).
  const double area = (L.x_max - L.x_min) * (L.y_max - L.y_min);
  double derived = 0.0;
  if (L.arrangement == LayerArrangement::File) {
    if (lt.has("seed")) lt.fail("seed", "not used with arrangement = \"file\"");
    const auto fraction = lt.optional_number("volume_fraction", Range::open(0.0, 0.9));
    const ParcelFileLimits limits{grid.x.start, grid.x.end, grid.y.start, grid.y.end, dem.particle_diameter,
                                  min_cell_width(grid)};
    const PlacedParcel defaults{0.0, 0.0, dem.parcel_diameter, 0.0, 0.0, 0.0, dem.initial_temperature};
    dem.layer_parcels = read_parcel_file(lt.path("file"), defaults, limits);
    // Parcels of diameter parcel_diameter that hold as many real particles (n ~ D^2, eq. 11).
    double equivalent = 0.0;
    for (const PlacedParcel& p : dem.layer_parcels) equivalent += std::pow(p.diameter / dem.parcel_diameter, 2);
    if (fraction) L.volume_fraction = *fraction;
    derived = fraction ? derived_real_per_parcel(*fraction, area, equivalent, dem.particle_diameter)
                       : equal_fraction_real_per_parcel(dem.parcel_diameter, dem.particle_diameter);
  } else {
    if (lt.has("file")) lt.fail("file", "only used with arrangement = \"file\"");
    // Above 0.9 no 2-D disc packing exists (hexagonal: 0.9069); the lattices need < ~0.78.
    L.volume_fraction = lt.number("volume_fraction", L.volume_fraction, Range::open(0.0, 0.9));
    L.seed = static_cast<std::uint64_t>(lt.integer("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));
    LayerLattice plan;
    try {
      plan = plan_layer(L, dem.parcel_diameter);
    } catch (const std::invalid_argument& e) {
      lt.fail("volume_fraction", e.what());
    }
    derived = derived_real_per_parcel(L.volume_fraction, area, static_cast<double>(plan.n_parcels),
                                      dem.particle_diameter);
  }
  lt.finish();
  dem.real_per_parcel = t.number("real_per_parcel", derived, Range::positive());

  dem.contact = parse_contact(t.table("contact"), dem.contact);
  dem.wall_contact = parse_contact(t.table("wall_contact"), dem.contact);

  // The parcels live in the gas domain: its edges are walls for them, except where the
  // gas is periodic (then the parcels are periodic too). Parcels never leave the grid.
  DemDomain& D = dem.domain;
  D.x_min = grid.x.start;
  D.x_max = grid.x.end;
  D.y_min = grid.y.start;
  D.y_max = grid.y.end;
  D.periodic_x = boundary.left == BoundaryKind::Periodic;
  D.wall_left = D.wall_right = !D.periodic_x;
  D.wall_bottom = D.wall_top = boundary.bottom != BoundaryKind::Periodic;
  if (boundary.bottom == BoundaryKind::Periodic) {
    t.fail("enabled", "parcels need walls at the bottom and top of the grid (boundary.bottom/top periodic)");
  }
  if (L.x_min < D.x_min || L.x_max > D.x_max || L.y_min < D.y_min || L.y_max > D.y_max) {
    t.fail("layer", "the layer rectangle must lie inside the grid");
  }

  dem.courant = t.number("courant", dem.courant, Range::open_closed(0.0, 0.5));
  dem.skin = t.number("skin", dem.skin, Range::open_closed(0.0, 1.0));
  dem.fast_skin_substeps = t.number("fast_skin_substeps", dem.fast_skin_substeps, Range::non_negative());
  const bool gravity = t.boolean("gravity", false);
  const double g = t.number("g", 9.81, Range::non_negative());
  dem.gravity_x = 0.0;
  dem.gravity_y = gravity ? -g : 0.0;
  t.finish();
}

}  // namespace dustlift::scene_detail
