// [particles]: the DEM parcel system (owned by the DEM module). The dust's material (diameter,
// density, contact stiffness, damping or restitution) has no defaults; the numerical settings
// default to the paper's (Table 2); choices where the paper is silent or garbled are explained
// in docs/dem.md.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "solver/dem/class_columns.hpp"
#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/size_distribution.hpp"
#include "solver/laws/contact.hpp"
#include "solver/scene/parcel_file.hpp"
#include "solver/scene/parse_sections.hpp"
#include "solver/scene/resource_limits.hpp"

namespace dustlift::scene_detail {
namespace {

/// Where a material property left out of a scene comes from: not a silent default but the
/// paper's dust, named so (with its value) in the resolved scene and the key reference.
std::string paper_material(double value) {
  return fmt::format("the paper's 100 um dust, {:g} (Tables 1, 2): not given, set it for your dust",
                     value);
}

/// [particles.contact], or [particles.wall_contact] whose defaults are the contact's
/// (`from` names it: they are derived, so a resolved scene with another contact law follows it).
/// The dashpot is given (`damping`) or follows from a normal restitution coefficient for a
/// pair of particles of reduced mass `m_eff` (at a wall: a particle of mass `m_eff`).
ContactParams parse_contact(TableReader t, const ContactParams& fallback, double m_eff,
                            const char* from = nullptr) {
  t.expect_keys({"k_n", "k_t", "damping", "restitution", "coulomb", "friction"});
  // The parcel-parcel law's constants are the paper's 100 um dust's unless given: they are
  // noted as taken from it (resolved scene, info), never silent.
  const auto number = [&](const char* key, double v, Range r) {
    return from != nullptr ? t.derived_number(key, v, std::string(from) + "." + key, r)
                           : t.derived_number(key, v, paper_material(v), r);
  };
  ContactParams c;
  // The parcel-parcel law's stiffness is the dust's (required); k_t follows the paper's ratio.
  c.k_n = from != nullptr ? number("k_n", fallback.k_n, Range::positive())
                          : t.required_number("k_n", Range::positive());
  c.k_t = from != nullptr
              ? number("k_t", fallback.k_t, Range::non_negative())
              : t.derived_number("k_t", 0.002 * c.k_n,
                                 t.full_key("k_n") + " (k_t = 0.002 k_n, the paper's ratio)",
                                 Range::non_negative());
  // A restitution is the material's: the dashpot follows for each pair's reduced mass
  // (docs/dem.md, "Restitution"); the one noted here is that of two particles of
  // particles.diameter (a wall: of one), which every pair has when the layer holds one size.
  const auto damping_of = [&](double e, const std::string& source) {
    return t.derived_number(
        "damping", damping_for_restitution(m_eff, c.k_n, e),
        source + ", k_n and the particles' mass (" +
            (from != nullptr ? "a particle at a wall" : "two particles of particles.diameter") +
            "; the run gives every pair its own)",
        Range::non_negative());
  };
  if (t.has("restitution")) {
    // The linear law's e_n = exp(-pi zeta / sqrt(1 - zeta^2)) inverted for the dashpot.
    if (t.has("damping")) t.fail("restitution", "give either damping or restitution, not both");
    c.restitution = t.required_number("restitution", Range::open_closed(0.0, 1.0));
    if (KeyFact* f = t.recorded_fact("restitution")) f->fallback = "optional (instead of damping)";
    c.damping = damping_of(c.restitution, t.full_key("restitution"));
  } else if (from != nullptr && !t.has("damping") && fallback.restitution > 0.0) {
    // The walls take the particles' restitution (the same material), each parcel's dashpot
    // following its own real mass.
    c.restitution =
        t.derived_number("restitution", fallback.restitution, std::string(from) + ".restitution",
                         Range::open_closed(0.0, 1.0));
    c.damping = damping_of(c.restitution, std::string(from) + ".restitution");
  } else if (from != nullptr) {
    c.damping = number("damping", fallback.damping, Range::non_negative());
  } else {
    if (!t.has("damping"))
      t.fail("damping", fmt::format("missing: give damping (N s/m) or restitution (0 < e <= 1; the "
                                    "dashpot then follows each pair's reduced mass, {:.4g} kg for "
                                    "two particles of particles.diameter)",
                                    m_eff));
    c.damping = t.required_number("damping", Range::non_negative());
  }
  const bool coulomb = from != nullptr
                           ? t.derived_boolean("coulomb", std::isfinite(fallback.friction),
                                               std::string(from) + ".coulomb")
                           : t.boolean("coulomb", std::isfinite(fallback.friction));
  if (coulomb) {
    c.friction = number("friction", std::isfinite(fallback.friction) ? fallback.friction : 0.5,
                        Range::non_negative());
  } else {
    if (t.has("friction")) t.fail("friction", "only used with coulomb = true");
    c.friction = std::numeric_limits<double>::infinity();
  }
  t.finish();
  return c;
}

/// The key reference's default of volume_fraction: a generated layer's, optional for a file.
void note_volume_fraction_default(TableReader& lt) {
  if (KeyFact* f = lt.recorded_fact("volume_fraction"))
    f->fallback =
        fmt::format("{:g} (with arrangement = \"file\": optional)", LayerConfig{}.volume_fraction);
}

/// particles.parcel_ratio: parcel diameter over particle diameter, one number for every size
/// class or one per class (`classes`; 0 for a layer of one size); empty when not given.
std::vector<double> parse_parcel_ratios(TableReader& t, std::size_t classes) {
  if (!t.has("parcel_ratio")) return {};
  if (t.has("parcel_diameter"))
    t.fail("parcel_ratio", "give either parcel_diameter or parcel_ratio, not both");
  const Range at_least_one = Range::closed(1.0, std::numeric_limits<double>::infinity());
  std::vector<double> ratios;
  if (t.is_array("parcel_ratio")) {
    ratios = t.number_list("parcel_ratio", {}, at_least_one);
    if (classes == 0 && ratios.size() != 1)
      t.fail("parcel_ratio",
             "a list of ratios needs [particles.size_distribution] (one per size class)");
    if (classes > 0 && ratios.size() != 1 && ratios.size() != classes)
      t.fail("parcel_ratio", fmt::format("has {} values for {} size classes: give one number, or "
                                         "one per class",
                                         ratios.size(), classes));
  } else {
    ratios.push_back(t.number("parcel_ratio", 1.0, at_least_one));
  }
  if (KeyFact* f = t.recorded_fact("parcel_ratio"))
    *f = KeyFact{"number or list of numbers", "none (particles.parcel_diameter)",
                 at_least_one.describe() + " (a parcel holds whole particles)"};
  return ratios;
}

LayerArrangement parse_arrangement(TableReader& lt) {
  std::array<std::string_view, kLayerArrangementNames.size()> names;
  for (std::size_t k = 0; k < names.size(); ++k) names[k] = kLayerArrangementNames[k].first;
  const std::string name = lt.choice("arrangement", "jittered_lattice", names);
  for (const auto& [known, value] : kLayerArrangementNames)
    if (known == name) return value;
  throw std::logic_error("parse_arrangement: a name choice() accepted has no arrangement");
}

/// What [particles] has read of the particle and parcel sizes, which the layer's parts need.
struct ParticleSizes {
  SizeDistribution dist;              ///< no classes: a layer of one size
  bool poly = false;                  ///< a size distribution gives the classes
  std::vector<double> ratios;         ///< particles.parcel_ratio (empty: not given)
  bool class_parcels = false;         ///< each class has parcels of its own size
  const char* size_key = "diameter";  ///< the key a user changes to get smaller parcels
};

/// The layer's real particles per parcel as its plan gives them.
struct LayerCounts {
  double area = 0.0;                 ///< m^2, the layer rectangle
  double derived = 0.0;              ///< real particles per parcel (a layer of one size)
  double planned = 0.0;              ///< a generated layer's planned parcel count
  std::vector<double> class_counts;  ///< parcels per class: each class's real count
};

/// particles.diameter, or the classes of [particles.size_distribution] (`sd`), whose mass
/// median particles.diameter then is (derived, so that it can never disagree with them).
SizeDistribution parse_particle_diameter(TableReader& t, TableReader& sd, DemConfig& dem) {
  SizeDistribution dist;
  if (sd.present()) dist = parse_size_distribution(sd);
  if (!dist.classes.empty()) {
    if (t.has("diameter")) {
      t.fail(
          "diameter",
          "derived from [particles.size_distribution] (its mass median diameter): remove it, the "
          "size classes give the particle sizes");
    }
    dem.size_classes = dist.classes;
    dem.particle_diameter = t.derived_number(
        "diameter", dist.mass_median, "particles.size_distribution (its mass median diameter)",
        Range::positive());
  } else {
    // The dust's size and density have no defaults: they are the user's dust's.
    dem.particle_diameter = t.required_number("diameter", Range::positive());
  }
  return dist;
}

/// particles.parcel_diameter, given or derived from the ratios (`z.ratios`, per class for
/// parcels of a size per class); sets the key a user changes to get smaller parcels.
void parse_parcel_diameter(TableReader& t, DemConfig& dem, ParticleSizes& z) {
  const bool parcel_diameter_given = t.has("parcel_diameter");
  if (z.class_parcels) {
    double largest = 0.0;
    for (std::size_t k = 0; k < dem.size_classes.size(); ++k) {
      SizeClass& c = dem.size_classes[k];
      c.parcel_diameter = z.ratios[z.ratios.size() == 1 ? 0 : k] * c.diameter;
      largest = std::max(largest, c.parcel_diameter);
    }
    dem.parcel_diameter = t.derived_number(
        "parcel_diameter", largest,
        "particles.parcel_ratio (the largest class's parcels; each class has its own)",
        Range::positive());
  } else if (!z.ratios.empty()) {
    dem.parcel_diameter =
        t.derived_number("parcel_diameter", z.ratios[0] * dem.particle_diameter,
                         "particles.parcel_ratio x particles.diameter", Range::positive());
  } else {
    dem.parcel_diameter =
        z.poly ? t.derived_number(
                     "parcel_diameter", z.dist.classes.back().diameter,
                     "particles.size_distribution (its largest class: no coarse graining of it)",
                     Range::positive())
               : t.derived_number("parcel_diameter", dem.particle_diameter,
                                  "particles.diameter (no coarse graining)", Range::positive());
  }
  if (dem.parcel_diameter < dem.particle_diameter) {
    t.fail("parcel_diameter", "must be at least the particle diameter (n_xy >= 1, eq. 11)");
  }
  z.size_key = parcel_diameter_given ? "parcel_diameter"
               : z.ratios.empty()    ? "diameter"
                                     : "parcel_ratio";
}

/// particles.layer's rectangle: x_min..x_max, and y_min..y_max or the thickness below y_max
/// (the bottom, and the floor grid.y.start, then follow from the top).
void parse_layer_rectangle(TableReader& lt, LayerConfig& L) {
  L.x_min = lt.number("x_min", L.x_min);
  L.x_max = lt.number("x_max", L.x_max);
  if (!(L.x_max > L.x_min)) lt.fail("x_max", "must be greater than x_min");
  const std::optional<double> thickness = lt.optional_number("thickness", Range::positive());
  L.y_max = lt.number("y_max", L.y_max);
  if (thickness) {
    const LayerFloor floor{L.y_max - *thickness, *thickness, L.y_max};
    L.y_min = lt.derived_number("y_min", floor.y, "particles.layer.thickness (y_max - thickness)");
    if (lt.has("y_min") && !agrees_with_floor(L.y_min, floor))
      lt.fail(
          "y_min",
          fmt::format(
              "{:.9g} m contradicts particles.layer.thickness = {:.9g} m, which puts the layer's "
              "bottom at y_max - thickness = {:.9g} m: give either particles.layer.y_min or "
              "particles.layer.thickness",
              L.y_min, *thickness, floor.y));
  } else {
    L.y_min = lt.number("y_min", L.y_min);
  }
  if (!(L.y_max > L.y_min)) lt.fail("y_max", "must be greater than y_min");
}

/// A layer read from a file (arrangement = "file"): its parcels and size classes, and the
/// real particles per parcel (n.derived).
void parse_layer_file(TableReader& t, TableReader& lt, DemConfig& dem, const GridConfig& grid,
                      const ParticleSizes& z, bool larger_than_cells, LayerCounts& n) {
  LayerConfig& L = dem.layer;
  if (z.poly) {
    t.fail("size_distribution",
           "not used with arrangement = \"file\": give the layer file a particle_diameter "
           "column instead (its distinct values are the size classes)");
  }
  if (lt.has("seed")) lt.fail("seed", "not used with arrangement = \"file\"");
  for (const char* key : {"loose_top_rows", "loose_top_fill"}) {
    if (lt.has(key))
      lt.fail(key, "not used with arrangement = \"file\" (thin the file's rows instead)");
  }
  if (lt.has("touching_columns"))
    lt.fail("touching_columns",
            "not used with arrangement = \"file\" (the file places the parcels)");
  const auto fraction = lt.optional_number("volume_fraction", Range::open(0.0, 0.9));
  note_volume_fraction_default(lt);
  const ParcelFileLimits limits{grid.x.start,
                                grid.x.end,
                                grid.y.start,
                                grid.y.end,
                                dem.particle_diameter,
                                larger_than_cells ? std::numeric_limits<double>::infinity()
                                                  : min_cell_width(grid) * (1.0 + kCellTolerance)};
  const PlacedParcel defaults{0.0, 0.0, dem.parcel_diameter,    0.0,
                              0.0, 0.0, dem.initial_temperature};
  dem.layer_parcels = read_parcel_file(lt.path("file"), defaults, limits);
  // Parcels of diameter parcel_diameter that hold as many real particles (n ~ D^2, eq. 11).
  double equivalent = 0.0;
  for (const PlacedParcel& p : dem.layer_parcels)
    equivalent += std::pow(p.diameter / dem.parcel_diameter, 2);
  if (fraction) L.volume_fraction = *fraction;
  dem.size_classes =
      file_size_classes(dem.layer_parcels, dem.particle_diameter, dem.parcel_diameter);
  n.derived = fraction
                  ? derived_real_per_parcel(*fraction, n.area, equivalent, dem.particle_diameter)
                  : equal_fraction_real_per_parcel(dem.parcel_diameter, dem.particle_diameter);
}

/// Refuses parcels larger than the layer's depth or the smallest cell (a size in the wrong
/// unit, 40 for 40 um, would otherwise surface as a packing error).
void check_parcel_size(TableReader& t, const DemConfig& dem, const GridConfig& grid,
                       const ParticleSizes& z, bool larger_than_cells) {
  const LayerConfig& L = dem.layer;
  const double depth = L.y_max - L.y_min;
  const double cell =
      larger_than_cells ? std::numeric_limits<double>::infinity() : min_cell_width(grid);
  if (dem.parcel_diameter > depth || dem.parcel_diameter > cell * (1.0 + kCellTolerance)) {
    t.fail(z.size_key,
           fmt::format("parcels of {:.9g} m are larger than {} ({:.9g} m){}", dem.parcel_diameter,
                       dem.parcel_diameter > depth ? "the layer's depth" : "the smallest grid cell",
                       dem.parcel_diameter > depth ? depth : cell,
                       z.ratios.empty() ? "; lengths are in metres (40 um is 40e-6)"
                                        : ": a smaller parcel ratio"));
  }
}

/// Refuses a layer of more parcels than the machine holds or the ids count (before the
/// lattice is planned: it is sized by the parcel count).
void check_parcel_count(TableReader& t, const DemConfig& dem, const ParticleSizes& z, double area) {
  const LayerConfig& L = dem.layer;
  double parcels = L.volume_fraction * area / disc_area(dem.parcel_diameter);
  if (z.class_parcels) {
    parcels = 0.0;
    for (const SizeClass& c : dem.size_classes)
      parcels += c.mass_fraction * L.volume_fraction * area / disc_area(c.parcel_diameter);
  }
  const std::string shortfall = memory_shortfall(0.0, parcels);
  if (!shortfall.empty() || parcels > static_cast<double>(kMaxParcels)) {
    t.fail(z.size_key,
           fmt::format("{:.9g} m parcels fill the layer with {:.3g} parcels: the run {}",
                       dem.parcel_diameter, parcels,
                       shortfall.empty() ? fmt::format("would need more than the {:.3g} parcel ids",
                                                       static_cast<double>(kMaxParcels))
                                         : shortfall));
  }
}

/// Parcels of a size per class, in columns of one class each (no lattice, no loose top,
/// class_columns.hpp): each class's real count.
std::vector<double> plan_class_parcels(TableReader& t, TableReader& lt, const DemConfig& dem) {
  for (const char* key : {"loose_top_rows", "loose_top_fill"}) {
    if (lt.has(key))
      lt.fail(key,
              "not used with particles.parcel_ratio and a size distribution (columns "
              "of one class each)");
  }
  try {
    return plan_class_columns(dem).real_per_parcel;
  } catch (const ClassColumnsError& e) {
    if (e.too_dense) lt.fail("volume_fraction", e.what());
    t.fail("parcel_ratio", e.what());
  }
}

/// A lattice layer: its plan, a looser top (docs/dem.md, "A looser top"), and the real
/// particles per parcel from the planned count (n.planned, n.derived).
void plan_lattice_layer(TableReader& lt, DemConfig& dem, const ParticleSizes& z,
                        const TableReader& sd, LayerCounts& n) {
  LayerConfig& L = dem.layer;
  LayerLattice plan;
  try {
    plan = plan_layer(L, dem.parcel_diameter);
  } catch (const std::invalid_argument& e) {
    lt.fail("volume_fraction", e.what());
  }
  // A looser top: the top rows keep a share of their sites.
  L.loose_top_rows =
      static_cast<int>(lt.integer("loose_top_rows", 0, 0, plan.rows, "the layer's rows"));
  L.loose_top_fill = lt.number("loose_top_fill", 1.0, Range::open_closed(0.0, 1.0));
  if (L.loose_top_fill != 1.0 && L.loose_top_rows == 0) {
    lt.fail("loose_top_fill", "needs loose_top_rows > 0 (the rows it thins)");
  }
  // From the plan's count: the rows below a loose top hold volume_fraction.
  n.planned = static_cast<double>(plan.n_parcels);
  n.derived = derived_real_per_parcel(L.volume_fraction, n.area, n.planned, dem.particle_diameter);
  if (z.poly) {
    const std::int64_t placed =
        L.loose_top_rows > 0
            ? static_cast<std::int64_t>(generate_layer(L, dem.parcel_diameter).x.size())
            : plan.n_parcels;
    check_class_counts(z.dist, sd, placed);
  }
}

/// A generated layer (a lattice, or columns of one class each): its checks, volume fraction,
/// seed and plan.
void parse_generated_layer(TableReader& t, TableReader& lt, TableReader& sd, DemConfig& dem,
                           const GridConfig& grid, const ParticleSizes& z, bool larger_than_cells,
                           LayerCounts& n) {
  LayerConfig& L = dem.layer;
  if (lt.has("file")) lt.fail("file", "only used with arrangement = \"file\"");
  if (z.poly && !larger_than_cells) check_class_sizes(z.dist, sd, dem, grid);  // before the plan
  check_parcel_size(t, dem, grid, z, larger_than_cells);
  // Above 0.9 no 2-D disc packing exists (hexagonal: 0.9069); the lattices need < ~0.78.
  L.volume_fraction = lt.number("volume_fraction", L.volume_fraction, Range::open(0.0, 0.9));
  note_volume_fraction_default(lt);
  L.seed = static_cast<std::uint64_t>(
      lt.integer("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));
  check_parcel_count(t, dem, z, n.area);
  if (z.class_parcels) {
    L.touching_columns = lt.boolean("touching_columns", L.touching_columns);
    n.class_counts = plan_class_parcels(t, lt, dem);
  } else {
    if (lt.has("touching_columns"))
      lt.fail("touching_columns",
              "only with particles.parcel_ratio and a size distribution (columns of one class "
              "each)");
    plan_lattice_layer(lt, dem, z, sd, n);
  }
}

/// particles.real_per_parcel: derived from the layer (one size), or one per size class,
/// noted in the resolved scene (docs/dem.md, "Polydisperse layers").
void parse_real_per_parcel(TableReader& t, DemConfig& dem, const ParticleSizes& z,
                           const LayerCounts& n) {
  if (!z.poly) {
    dem.real_per_parcel =
        t.derived_number("real_per_parcel", n.derived,
                         "the layer's volume_fraction and the particle and parcel diameters (§4)",
                         Range::positive());
    return;
  }
  // Per class: every parcel holds the same solid volume.
  if (t.has("real_per_parcel")) {
    t.fail("real_per_parcel",
           "not used with [particles.size_distribution]: each size class has its own "
           "count, derived so that every parcel holds the same solid volume");
  }
  std::string per_class = "[";
  for (std::size_t k = 0; k < z.dist.classes.size(); ++k) {
    per_class += fmt::format("{}{:.17g}", k ? ", " : "",
                             z.class_parcels
                                 ? n.class_counts[k]
                                 : derived_real_per_parcel(dem.layer.volume_fraction, n.area,
                                                           n.planned, z.dist.classes[k].diameter));
  }
  t.note_derived(
      "real_per_parcel", per_class + "]",
      z.class_parcels
          ? "one per size class: its columns hold the layer's volume_fraction (docs/dem.md, "
            "\"Parcels per class\")"
          : "one per size class: the layer's volume_fraction shared equally by its parcels (§4)");
  dem.real_per_parcel = 0.0;  // derived per class by the layer generator
}

/// The parcels live in the gas domain: its edges are walls for them, except where the gas is
/// periodic (then the parcels are periodic too). Parcels never leave the grid, and the layer
/// rectangle must lie inside it.
void set_particle_domain(TableReader& t, TableReader& lt, DemConfig& dem, const GridConfig& grid,
                         const BoundaryConfig& boundary) {
  const LayerConfig& L = dem.layer;
  DemDomain& D = dem.domain;
  D.x_min = grid.x.start;
  D.x_max = grid.x.end;
  D.y_min = grid.y.start;
  D.y_max = grid.y.end;
  D.periodic_x = boundary.left == BoundaryKind::Periodic;
  D.wall_left = D.wall_right = !D.periodic_x;
  D.wall_bottom = D.wall_top = boundary.bottom != BoundaryKind::Periodic;
  if (boundary.bottom == BoundaryKind::Periodic) {
    t.fail("enabled",
           "parcels need walls at the bottom and top of the grid (boundary.bottom/top periodic)");
  }
  // Which edge leaves the grid, against the grid's bounds.
  const struct {
    const char* key;
    double value, bound;
    bool outside;
    const char* side;
  } edges[] = {{"x_min", L.x_min, D.x_min, L.x_min < D.x_min, "grid.x.start"},
               {"x_max", L.x_max, D.x_max, L.x_max > D.x_max, "grid.x.end"},
               {"y_min", L.y_min, D.y_min, L.y_min < D.y_min, "grid.y.start"},
               {"y_max", L.y_max, D.y_max, L.y_max > D.y_max, "grid.y.end"}};
  for (const auto& e : edges) {
    if (e.outside)
      lt.fail(e.key,
              fmt::format(
                  "{:.9g} m lies outside the grid ({} = {:.9g} m): the layer rectangle must lie "
                  "inside x in [{:.9g}, {:.9g}] m, y in [{:.9g}, {:.9g}] m",
                  e.value, e.side, e.bound, D.x_min, D.x_max, D.y_min, D.y_max));
  }
}

/// The DEM's numerical settings: its Courant number, the neighbour skin and the fast parcels'.
void parse_dem_numerics(TableReader& t, DemConfig& dem) {
  dem.courant = t.number("courant", dem.courant, Range::open_closed(0.0, 0.5));
  if (dem.courant < kMinCourant) {
    t.fail("courant",
           fmt::format(
               "{:g} is below {:g}: the DEM would take more than {:g} times the sub-steps of "
               "the default {:g} (eq. 18), which buys no accuracy",
               dem.courant, kMinCourant, DemConfig{}.courant / kMinCourant, DemConfig{}.courant));
  }
  dem.skin = t.number("skin", dem.skin, Range::open_closed(0.0, 1.0));
  dem.fast_skin_substeps =
      t.number("fast_skin_substeps", dem.fast_skin_substeps, Range::non_negative());
}

/// Gravity on the parcels: true (g along -y) or a vector [g_x, g_y] in m/s^2 (a vertical
/// tube along x has it along -x).
void parse_gravity(TableReader& t, DemConfig& dem) {
  if (t.is_array("gravity")) {
    if (t.has("g"))
      t.fail("g", "only used with gravity = true (a gravity vector gives its own magnitude)");
    const std::vector<double> g = t.number_list("gravity", {}, Range{});
    if (g.size() != 2)
      t.fail("gravity", "a gravity vector has two components, [g_x, g_y] in m/s^2");
    dem.gravity_x = g[0];
    dem.gravity_y = g[1];
  } else {
    const bool gravity = t.boolean("gravity", false);
    if (!gravity && t.has("g")) t.fail("g", "only used with gravity = true");
    const double g = gravity ? t.number("g", 9.81, Range::non_negative()) : 0.0;
    dem.gravity_x = 0.0;
    dem.gravity_y = -g;
  }
  // Either form, whichever this scene used.
  if (KeyFact* f = t.recorded_fact("gravity"))
    *f = KeyFact{"boolean or list of numbers", "false", "true (g along -y), false, or [g_x, g_y]"};
}

}  // namespace

std::optional<LayerFloor> read_layer_floor(TableReader& root) {
  TableReader layer = root.lookahead("particles").lookahead("layer");
  if (!layer.has("thickness")) return std::nullopt;
  LayerFloor floor;
  floor.thickness =
      *layer.optional_number("thickness", Range::positive());  // present (has() above)
  floor.y_max = layer.number("y_max", LayerConfig{}.y_max);
  floor.y = floor.y_max - floor.thickness;
  return floor;
}

bool agrees_with_floor(double y, const LayerFloor& floor) {
  return std::abs(y - floor.y) <= 1e-9 * (floor.thickness + std::abs(floor.y_max));
}

void parse_particles(TableReader t, DemConfig& dem, const GridConfig& grid,
                     const BoundaryConfig& boundary, bool larger_than_cells) {
  t.expect_keys({"enabled", "diameter", "density", "heat_capacity", "temperature",
                 "parcel_diameter", "parcel_ratio", "layer", "real_per_parcel", "contact",
                 "wall_contact", "cohesion", "courant", "skin", "fast_skin_substeps", "gravity",
                 "g", "size_distribution"});
  dem.enabled = t.boolean("enabled", t.present());
  if (KeyFact* f = t.recorded_fact("enabled")) f->fallback = "true when [particles] is present";
  if (!dem.enabled) {
    // Switched off on purpose: the rest of the section (and the dust's coupling and output
    // keys) stays as written, unread, so one override turns the dust off.
    dem.switched_off = t.has("enabled");
    if (!dem.switched_off) t.finish();
    return;
  }
  // A polydisperse layer: its classes give the particle sizes.
  TableReader sd = t.table("size_distribution");
  ParticleSizes z;
  z.dist = parse_particle_diameter(t, sd, dem);
  z.poly = !z.dist.classes.empty();
  dem.density = t.required_number("density", Range::positive());
  dem.heat_capacity = t.number("heat_capacity", dem.heat_capacity, Range::positive());
  dem.initial_temperature = t.number("temperature", dem.initial_temperature, Range::positive());
  check_plausible_temperature(t, "temperature", dem.initial_temperature);
  // Coarse graining by a ratio: each class's parcels are ratio x its particles wide.
  z.ratios = parse_parcel_ratios(t, z.dist.classes.size());
  z.class_parcels = z.poly && !z.ratios.empty();
  parse_parcel_diameter(t, dem, z);

  TableReader lt = t.table("layer");
  lt.expect_keys({"x_min", "x_max", "y_min", "y_max", "thickness", "arrangement", "settle", "seed",
                  "volume_fraction", "file", "loose_top_rows", "loose_top_fill",
                  "touching_columns"});
  LayerConfig& L = dem.layer;
  parse_layer_rectangle(lt, L);
  L.arrangement = parse_arrangement(lt);
  const bool settled = L.arrangement == LayerArrangement::Settled;
  L.settle = lt.derived_boolean("settle", settled || L.settle, "particles.layer.arrangement");
  if (settled && !L.settle) lt.fail("settle", "arrangement = \"settled\" always settles the layer");
  // Real particles per parcel per metre of depth (§4), derived unless the scene sets it:
  // the layer rectangle then holds volume_fraction of solid in 3-D (15,024 /m for the
  // paper's layer). A layer file without volume_fraction fills each parcel's disc to the
  // plane's fraction instead, (pi D^2/4) / V_p (15,000 /m for 100 um).
  LayerCounts n;
  n.area = (L.x_max - L.x_min) * (L.y_max - L.y_min);
  if (!z.ratios.empty() && L.arrangement == LayerArrangement::File)
    t.fail("parcel_ratio",
           "not used with arrangement = \"file\": the file gives each parcel's diameter");
  if (z.class_parcels && L.arrangement != LayerArrangement::Columnar) {
    t.fail("parcel_ratio",
           fmt::format("with [particles.size_distribution] each class has parcels of its own "
                       "size, packed in columns of one class each: set "
                       "particles.layer.arrangement = \"columnar\" (not \"{}\")",
                       layer_arrangement_name(L.arrangement)));
  }
  if (L.arrangement == LayerArrangement::File) {
    parse_layer_file(t, lt, dem, grid, z, larger_than_cells, n);
  } else {
    parse_generated_layer(t, lt, sd, dem, grid, z, larger_than_cells, n);
  }
  lt.finish();
  parse_real_per_parcel(t, dem, z, n);

  // Restitution is of two particles of particles.diameter (reduced mass m/2), or of one at a wall
  // (m).
  const double particle_mass = dem.density * sphere_volume(dem.particle_diameter);
  dem.contact = parse_contact(t.table("contact", true), dem.contact, 0.5 * particle_mass);
  dem.wall_contact =
      parse_contact(t.table("wall_contact"), dem.contact, particle_mass, "particles.contact");
  parse_cohesion(t.table("cohesion"), dem);
  set_particle_domain(t, lt, dem, grid, boundary);
  parse_dem_numerics(t, dem);
  parse_gravity(t, dem);
  t.finish();
}

}  // namespace dustlift::scene_detail
