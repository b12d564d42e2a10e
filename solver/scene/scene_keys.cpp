// The scene keys' units and meanings (scene_keys.hpp). The defaults, ranges and types are not
// written here: the parser records them as it reads (KeyFact), so they cannot drift from it.
#include "solver/scene/scene_keys.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace dustlift {
namespace {

constexpr SceneKeyDoc kDocs[] = {
    // [run]
    {"run", "", "the run: its name, end time and step limits"},
    {"run.name", "", "the run's name (log, files' field data)"},
    {"run.end_time", "s", "simulated time at which the run ends"},
    {"run.max_steps", "1", "stop after this many steps (0: no limit)"},
    {"run.progress_interval", "s", "wall time between progress lines in the log"},
    {"run.skip_at_rest", "", "skip gas cells and parcels that rest (false: compute every one)"},
    {"run.exact", "",
     "skip only what rests exactly: bitwise the results of no skipping (run.rest_tolerance 0)"},
    {"run.rest_tolerance", "1",
     "skip what is within this relative change of rest too (changes results at that level, "
     "within the chaos floor; 0: exact)"},
    {"run.rebalance_steps", "1",
     "MPI: steps between moves of the slab cuts that follow the work (0: never)"},
    {"run.allow_implausible", "",
     "accept a gas pressure below 1 kPa or a temperature below 100 K (refused otherwise as a "
     "probable unit slip)"},
    // [grid]
    {"grid", "", "the rectilinear grid: [grid.x] along the channel, [grid.y] up"},
    {"grid.*", "",
     "one axis: uniform (cells) or a uniform core with geometrically stretched ends (cell_size)"},
    {"grid.*.start", "m", "the axis' first face (y: the floor)"},
    {"grid.*.end", "m", "the axis' last face"},
    {"grid.*.cells", "1", "cells of a uniform axis (not with cell_size)"},
    {"grid.*.cell_size", "m", "cell width of the uniform core"},
    {"grid.*.uniform_start", "m", "where the uniform core starts (cells below it are stretched)"},
    {"grid.*.uniform_end", "m", "where the uniform core ends (cells above it are stretched)"},
    {"grid.*.cells_below", "1", "stretched cells between start and uniform_start"},
    {"grid.*.cells_above", "1", "stretched cells between uniform_end and end"},
    // [gas]
    {"gas", "", "the gas model and scheme"},
    {"gas.thermo", "",
     "thermally perfect air (NASA polynomials, O2:N2 = 1:3.76) or a calorically perfect gas"},
    {"gas.gamma", "1", "ratio of specific heats (calorically perfect gas)"},
    {"gas.gas_constant", "J/(kg K)", "specific gas constant"},
    {"gas.gravity", "m/s^2", "body acceleration [g_x, g_y] on the gas"},
    {"gas.transport", "", "viscosity and heat conduction"},
    {"gas.transport.model", "",
     "Euler (inviscid), constant mu, Sutherland's law, or Gordon's fits with Wilke's mixing rule"},
    {"gas.transport.viscosity", "Pa s", "dynamic viscosity of the constant model"},
    {"gas.transport.prandtl", "1", "Prandtl number (constant and Sutherland models)"},
    {"gas.transport.sutherland_mu_ref", "Pa s",
     "Sutherland: viscosity at the reference temperature"},
    {"gas.transport.sutherland_t_ref", "K", "Sutherland: reference temperature"},
    {"gas.transport.sutherland_s", "K", "Sutherland's constant"},
    {"gas.scheme", "", "the convective scheme (SLAU2 fluxes, SSP-RK3 in time)"},
    {"gas.scheme.reconstruction", "", "first order, or MUSCL of 2nd or 3rd order (kappa = 1/3)"},
    {"gas.scheme.limiter", "", "slope limiter of the MUSCL reconstruction"},
    {"gas.scheme.minmod_b", "1", "compression parameter b of the minmod limiter"},
    {"gas.scheme.cfl", "1", "Courant number of the gas time step"},
    // [boundary]
    {"boundary", "", "the grid's four edges"},
    {"boundary.left", "", "the edge at grid.x.start"},
    {"boundary.right", "", "the edge at grid.x.end"},
    {"boundary.bottom", "", "the floor, at grid.y.start"},
    {"boundary.top", "", "the edge at grid.y.end"},
    {"boundary.inflow", "",
     "the state an inflow edge holds (default: the initial state beside it)"},
    // [initial]
    {"initial", "", "the gas at t = 0"},
    {"initial.kind", "",
     "uniform state, a Riemann problem, or a shock of given Mach number into a state at rest"},
    {"initial.state", "", "uniform: the state; shock: the quiescent state ahead of the shock"},
    {"initial.left", "", "Riemann: the state below position"},
    {"initial.right", "", "Riemann: the state above position"},
    {"initial.position", "m", "Riemann and shock: where the split or the shock is"},
    {"initial.axis", "", "Riemann and shock: the split's normal (the shock moves towards +axis)"},
    {"initial.mach", "1", "shock: Mach number relative to the sound speed of the state ahead"},
    // A gas state: initial.state, initial.left, initial.right, boundary.inflow.
    {"*.*.p", "Pa", "a gas state's pressure"},
    {"*.*.rho", "kg/m^3", "a gas state's density (give rho or T)"},
    {"*.*.T", "K", "a gas state's temperature (give rho or T)"},
    {"*.*.u", "m/s", "a gas state's velocity along x"},
    {"*.*.v", "m/s", "a gas state's velocity along y"},
    // [particles]
    {"particles", "", "the dust: real particles, DEM parcels, the layer"},
    {"particles.enabled", "",
     "false switches the dust off (the rest of the dust's settings stay unread)"},
    {"particles.diameter", "m",
     "real particle diameter (derived: the mass median of a size distribution)"},
    {"particles.density", "kg/m^3", "material density of the real particles"},
    {"particles.heat_capacity", "J/(kg K)", "specific heat of the particles"},
    {"particles.temperature", "K", "the particles' temperature at t = 0"},
    {"particles.parcel_diameter", "m",
     "DEM parcel diameter n_xy d (coarse graining; at most the smallest cell)"},
    {"particles.parcel_ratio", "1",
     "parcel diameter over particle diameter (coarse graining): one number, or one per size "
     "class; with a size distribution each class gets parcels of its own size, packed in "
     "columns of one class each (columnar layers)"},
    {"particles.real_per_parcel", "1/m",
     "real particles per parcel per metre of span (masses are per metre of span)"},
    {"particles.courant", "1",
     "nu_DEM: DEM sub-step = nu sqrt(smallest real-particle mass / largest spring constant)"},
    {"particles.skin", "1", "neighbour-list skin, in parcel diameters"},
    {"particles.fast_skin_substeps", "1", "sub-steps a fast parcel's skin covers at its speed"},
    {"particles.gravity", "m/s^2", "true (g along -y) or a vector [g_x, g_y] on the parcels"},
    {"particles.g", "m/s^2", "the magnitude with gravity = true"},
    {"particles.layer", "", "the rectangle the layer generator fills with parcels at rest"},
    {"particles.layer.x_min", "m", "the layer's upstream end"},
    {"particles.layer.x_max", "m", "the layer's downstream end"},
    {"particles.layer.y_min", "m", "the layer's bottom"},
    {"particles.layer.y_max", "m", "the layer's top (heights in the outputs count from it)"},
    {"particles.layer.thickness", "m",
     "the layer's depth: y_min = y_max - thickness, and the floor grid.y.start follows (give "
     "thickness or y_min)"},
    {"particles.layer.volume_fraction", "1",
     "3-D solid volume fraction of the layer (the parcels' 2-D areal fraction equals it)"},
    {"particles.layer.arrangement", "",
     "how parcels are placed: lattice, jittered lattice, touching columns, offset rows, settled "
     "under gravity, or a file"},
    {"particles.layer.settle", "", "let the layer settle under gravity before t = 0"},
    {"particles.layer.seed", "1",
     "seed of the random placement and of the size classes' assignment"},
    {"particles.layer.file", "",
     "arrangement = \"file\": CSV of x, y, diameter, vx, vy, omega, temperature, "
     "particle_diameter"},
    {"particles.layer.loose_top_rows", "1", "the top rows that keep only a share of their sites"},
    {"particles.layer.loose_top_fill", "1", "the share of sites the loose top rows keep"},
    {"particles.layer.touching_columns", "",
     "columns of one class each side by side, every parcel touching its neighbours; the real "
     "particles per parcel hold volume_fraction"},
    {"particles.size_distribution", "",
     "a polydisperse layer: discrete classes, or a log-normal mass distribution cut into classes"},
    {"particles.size_distribution.diameters", "m",
     "discrete classes: real particle diameters, ascending"},
    {"particles.size_distribution.mass_fractions", "1",
     "discrete classes: each class's share of the layer's mass (sum 1)"},
    {"particles.size_distribution.median", "m", "log-normal: mass median diameter"},
    {"particles.size_distribution.geometric_std", "1",
     "log-normal: geometric standard deviation sigma_g (> 1)"},
    {"particles.size_distribution.classes", "1",
     "log-normal: the equal-mass classes it is cut into"},
    {"particles.contact", "", "the parcel-parcel spring-dashpot contact, per real particle"},
    {"particles.wall_contact", "", "the parcel-wall contact (default: the parcel-parcel one)"},
    {"particles.*.k_n", "N/m", "normal spring constant"},
    {"particles.*.k_t", "N/m", "tangential spring constant"},
    {"particles.*.damping", "N s/m",
     "dashpot coefficient, normal and tangential (or give restitution)"},
    {"particles.*.restitution", "1",
     "the material's normal restitution coefficient: every pair's dashpot follows from its "
     "reduced mass, every parcel's at a wall from its particle's mass (the walls take the "
     "particles' by default)"},
    {"particles.cohesion", "",
     "van der Waals cohesion per pair of real particles, held at its pull-off force while the "
     "parcels touch (off without the table)"},
    {"particles.cohesion.hamaker", "J",
     "Hamaker constant A: pull-off force A R*/(6 s0^2) of a real pair (Hamaker 1937); about "
     "5e-20 to 7e-20 J for organic solids, 6e-20 to 1e-19 J for quartz and mica "
     "(Israelachvili 2011, ch. 13); 0: no cohesion"},
    {"particles.cohesion.surface_energy", "J/m^2",
     "surface energy gamma per surface instead of hamaker: pull-off 4 pi gamma R* (DMT), "
     "A = 24 pi gamma s0^2"},
    {"particles.cohesion.min_separation", "m",
     "s0, the gap of surfaces in contact, where the force saturates (0.4 nm: Krupp 1967)"},
    {"particles.cohesion.asperity_radius", "m",
     "radius of Rumpf's surface asperity (Rumpf 1990): a rough surface's far weaker pull"},
    {"particles.cohesion.cutoff", "m",
     "largest surface gap with a force, the Hamaker tail A R*/(6 s^2) (0: only while the parcels "
     "overlap)"},
    {"particles.cohesion.wall_hamaker", "J", "Hamaker constant of a particle and a wall"},
    {"particles.cohesion.wall_surface_energy", "J/m^2",
     "surface energy of a particle and a wall instead of wall_hamaker"},
    {"particles.*.coulomb", "", "limit the tangential force to friction times the normal force"},
    {"particles.*.friction", "1", "Coulomb friction coefficient"},
    // [coupling]
    {"coupling", "", "the gas-particle effects (each on or off)"},
    {"coupling.two_way", "", "the particles act back on the gas (porosity and exchange terms)"},
    {"coupling.drag", "",
     "drag (Clift-Gauvin with Parmar's compressibility and the dense-array factor)"},
    {"coupling.compressibility_correction", "",
     "Parmar et al.'s Mach-number factor of the drag (not with the osnes and tenneti closures)"},
    {"coupling.volume_fraction_correction", "",
     "the drag among other particles: Sangani et al.'s factor (the paper's), the closures of "
     "Osnes et al. 2023 or Tenneti et al. 2011 for dense suspensions, linear, or none"},
    {"coupling.volume_fraction_cap", "1",
     "the solid fraction at which the dense-array factor stops growing"},
    {"coupling.magnus", "", "the Magnus (rotational) lift force"},
    {"coupling.magnus_coefficient", "1", "C_LM of the Magnus force"},
    {"coupling.magnus_convention", "", "the paper's sign convention or the standard one"},
    {"coupling.lun_liu", "", "Lun & Liu's Reynolds-number dependence of the lift coefficient"},
    {"coupling.pressure_force", "", "the pressure-gradient force -V_p grad p"},
    {"coupling.added_mass", "", "the inviscid-unsteady (added-mass) force of Parmar et al."},
    {"coupling.added_mass_volume_fraction", "",
     "how C_M grows with the solid fraction: Beguin et al. 2016 (1 + 0.68 phi^2), Zuber 1964 "
     "((1 + 2 phi)/(1 - phi)), or none"},
    {"coupling.added_mass_fluid_acceleration", "",
     "the gas's momentum rate D(rho u)/Dt in the added mass: the resolved gas's, or -grad p "
     "(Ling et al. 2012, dilute clouds)"},
    {"coupling.finite_size", "",
     "the pressure-gradient force and the added mass's fluid part averaged over the particle's "
     "volume (Faxen form), for particles larger than the cells"},
    {"coupling.rotation_torque", "",
     "the fluid torque on a spinning particle (Dennis, Singh & Ingham)"},
    {"coupling.torque_stokes_below", "1",
     "rotational Reynolds number below which the Stokes torque is used"},
    {"coupling.heat_transfer", "",
     "convective heat transfer (Ranz-Marshall) and the particle temperature"},
    {"coupling.interpolation", "", "how gas values are sampled at a parcel: triangle or bilinear"},
    {"coupling.influence_width", "m",
     "width of the kernel that deposits a parcel's volume and exchange on the cells"},
    {"coupling.max_volume_fraction", "1",
     "largest particle volume fraction the gas sees (porosity floor 1 - this)"},
    // [output]
    {"output", "", "files, series and checkpoints"},
    {"output.interval", "s",
     "simulated time between VTK outputs and series rows (0: start and end only)"},
    {"output.vtk", "", "write gas.pvd and parcels.pvd"},
    {"output.shock_threshold", "1", "relative pressure rise that marks the shock"},
    {"output.checkpoint_interval", "s",
     "simulated time between checkpoints (0: none by simulated time)"},
    {"output.checkpoint_wall_interval", "s",
     "wall time after which the next step writes a checkpoint (0: none)"},
    {"output.surface_threshold", "1", "alpha_p level that defines the dust surface"},
    {"output.surface_stations", "m", "x of the columns whose surface height is a series"},
    {"output.bands", "",
     "force-history bands: parcels that start in a box (default: the paper's two)"},
    {"output.bands.name", "", "the band's name (series forces_<name>)"},
    {"output.bands.x_min", "m", "the box's upstream end"},
    {"output.bands.x_max", "m", "the box's downstream end"},
    {"output.bands.y_min", "m", "the box's bottom"},
    {"output.bands.y_max", "m", "the box's top"},
    {"output.band_bin_width", "s", "bins of the time since shock arrival"},
    {"output.band_duration", "s", "the last bin's end"},
    {"output.contact_window", "s", "averaging window of the contact force"},
    {"output.probes", "", "gauges: the gas values of the cell holding a point"},
    {"output.probes.name", "", "the probe's name (columns <name>_<field>)"},
    {"output.probes.x", "m", "the point's x"},
    {"output.probes.y", "m", "the point's y"},
    {"output.probes.fields", "", "what to record: p, rho, u, v, T, mach, alpha_p"},
    {"output.probe_interval", "s", "simulated time between probe samples (0: every step)"},
    {"output.parcel_fronts", "",
     "series of the parcels' x-extent (a particle curtain's fronts) and of the force parts "
     "summed over the particles"},
    {"output.line_of_sight", "",
     "how parcel_fronts sees the cloud across the channel, as a schlieren or shadowgraph image "
     "through the tube does"},
    {"output.line_of_sight.depth", "m",
     "the path through the cloud along the line of sight (the tube's width)"},
    {"output.line_of_sight.optical_depth", "1",
     "the edge: where n (pi d^2 / 4) depth of the real particles falls below this (1: the light "
     "dimmed to 1/e)"},
    {"output.line_of_sight.bin", "m", "width of the streamwise bins the optical depth is made in"},
    {"output.dust_cloud", "",
     "series of the lifted dust cloud (mass, heights, explosible band of the filtered "
     "concentration, entrainment, distances behind the shock), its concentration histogram and "
     "its entrainment along the channel"},
    {"output.cloud_lift_height", "m",
     "a parcel is lifted (has left the layer) when its centre is this far above the initial "
     "layer top"},
    {"output.cloud_top_concentration", "kg/m^3",
     "flow-grid dust concentration that marks the cloud's top (replaces "
     "cloud_edge_concentration in g/m^3, which is refused)"},
    {"output.cloud_filter_width", "m",
     "side of the square box the filtered dust concentration is read in, sliding in steps of a "
     "ninth of it (one parcel alone in a box: the quantum)"},
    {"output.explosible_lower", "kg/m^3",
     "lower edge of the explosible band: a minimum explosible concentration (0.05: coal, starch "
     "and grain dusts lie at 0.03-0.06; Eckhoff 2003, ch. 1). Replaces explosible_concentration "
     "(g/m^3), which is refused"},
    {"output.explosible_upper", "kg/m^3",
     "upper edge of the explosible band (2: the low end of the few kg/m^3 upper limits reported "
     "for such dusts; Eckhoff 2003, ch. 1)"},
    {"output.fines_diameter", "m",
     "real particles smaller than this are the fines (75 um: the No. 200 sieve of float coal "
     "dust, US 30 CFR 75.400-1)"},
    {"output.entrainment_heights", "m",
     "heights above the initial layer top of the vertical dust mass fluxes"},
    {"output.entrainment_bin_width", "m", "stretches of channel of series dust_entrainment"},
    // [insitu]
    {"insitu", "", "in-situ visualisation"},
    {"insitu.catalyst", "", "ParaView Catalyst pipelines run on the live state"},
    {"insitu.catalyst.scripts", "", "Catalyst Python scripts"},
    {"insitu.catalyst.interval_steps", "1", "deliver every this many steps"},
    {"insitu.catalyst.interval", "s",
     "simulated time between deliveries (not with interval_steps)"},
    {"insitu.catalyst.live", "", "also a pipeline that connects to ParaView Live"},
    {"insitu.catalyst.live_url", "", "host:port of the ParaView GUI for Live"},
};

bool matches(std::string_view pattern, std::string_view key) {
  while (true) {
    const std::size_t p = pattern.find('.'), k = key.find('.');
    const std::string_view ps = pattern.substr(0, p), ks = key.substr(0, k);
    if (ps != "*" && ps != ks) return false;
    if (p == std::string_view::npos || k == std::string_view::npos) return p == k;
    pattern.remove_prefix(p + 1);
    key.remove_prefix(k + 1);
  }
}

std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

/// The reference's default of a key whose scenes record different ones (`earlier` merged
/// first): required unless another key gives it (a size distribution, a restitution); a
/// literal default that another key can replace keeps both ("-0.002, or from ..."); of two
/// derived texts the later one wins.
std::string combined_fallback(const std::string& earlier, const std::string& later) {
  const auto derived = [](const std::string& f) { return f.rfind("from ", 0) == 0; };
  // A value a scene gets when it leaves the key out (not a placeholder such as [] or none).
  const auto literal = [&](const std::string& f) {
    return !derived(f) && f != "required" && f != "optional" && f != "none" && f != "[]" &&
           f != "\"\"" && f.find(", or ") == std::string::npos;
  };
  if (earlier.rfind("required, or ", 0) == 0) return earlier;
  if (earlier == "required" && derived(later)) return "required, or " + later;
  if (later == "required" && derived(earlier)) return "required, or " + earlier;
  if (literal(earlier) && derived(later)) return earlier + ", or " + later;
  if (derived(earlier) && literal(later)) return later + ", or " + earlier;
  if (earlier.find(", or ") != std::string::npos && (derived(later) || literal(later)))
    return earlier;
  if (derived(later)) return later;
  if (derived(earlier)) return earlier;
  return "depends on the scene";
}

/// `text` with the names a key's wildcard segments stand for written as the pattern writes
/// them: for grid.y.uniform_start (pattern grid.*.uniform_start), "from grid.y.start" reads
/// "from grid.*.start", the same axis's start.
std::string generic_text(std::string text, std::string_view pattern, std::string_view key) {
  std::string concrete, generic;
  while (true) {
    const std::size_t p = pattern.find('.'), k = key.find('.');
    const std::string_view ps = pattern.substr(0, p), ks = key.substr(0, k);
    concrete += std::string(ks) + ".";
    generic += std::string(ps) + ".";
    if (ps == "*" && concrete != generic) {
      for (std::size_t at = text.find(concrete); at != std::string::npos;
           at = text.find(concrete, at + generic.size()))
        text.replace(at, concrete.size(), generic);
    }
    if (p == std::string_view::npos || k == std::string_view::npos) break;
    pattern.remove_prefix(p + 1);
    key.remove_prefix(k + 1);
  }
  return text;
}

KeyFact generic_fact(const KeyFact& f, std::string_view pattern, std::string_view key) {
  return KeyFact{f.kind, generic_text(f.fallback, pattern, key),
                 generic_text(f.range, pattern, key)};
}

bool same_fact(const KeyFact& a, const KeyFact& b) {
  return a.kind == b.kind && a.fallback == b.fallback && a.range == b.range;
}

/// A section's heading: the table, or for the gas states' keys (*.*.p, ...) what they are.
std::string section_title(const std::string& top) {
  if (top == "*")
    return "A gas state: `initial.state`, `initial.left`, `initial.right`, `boundary.inflow`";
  return "[" + top + "]";
}

}  // namespace

std::span<const SceneKeyDoc> scene_key_docs() {
  return kDocs;
}

const SceneKeyDoc* find_key_doc(std::string_view key) {
  for (const SceneKeyDoc& d : kDocs)
    if (matches(d.pattern, key)) return &d;
  return nullptr;
}

void merge_key_facts(std::map<std::string, KeyFact>& into,
                     const std::map<std::string, KeyFact>& from) {
  for (const auto& [key, fact] : from) {
    auto [it, inserted] = into.try_emplace(key, fact);
    if (inserted) continue;
    KeyFact& have = it->second;
    if (have.kind.empty()) have.kind = fact.kind;
    if (have.range.empty()) have.range = fact.range;
    if (have.fallback.empty())
      have.fallback = fact.fallback;
    else if (!fact.fallback.empty() && fact.fallback != have.fallback)
      have.fallback = combined_fallback(have.fallback, fact.fallback);
  }
}

std::string key_reference_markdown(const std::map<std::string, KeyFact>& facts) {
  // One row per documented pattern (or per key where the keys of a pattern differ), with the
  // facts of the keys it matches.
  std::string out =
      "# Scene keys\n\n"
      "Every key a scene file (TOML) may hold: its type, unit, default and allowed values as the "
      "parser reads them, and what it means. Units are SI; masses are per metre of span (the 2-D "
      "run's depth). A default \"from ...\" is derived from other keys when the key is not set "
      "(`dustlift info SCENE` prints the value it takes); \"required\" keys have none; "
      "\"optional\" sections and keys are used only when present. A `*` stands for any one name "
      "(`grid.*.cells`: `grid.x.cells`, `grid.y.cells`; `initial.*.p`: the pressure of "
      "`initial.state`, `initial.left`, `initial.right`); in a default or a range it stands for "
      "the same name as in the key (`grid.*.uniform_start` of the y axis comes from "
      "`grid.y.start`). The allowed values are the limits the parser checks; limits set by other "
      "keys are named by them. A gas pressure below 1 kPa and a temperature below 100 K are "
      "refused as a probable slip of the unit (Pa, K) unless `run.allow_implausible = true`.\n\n"
      "Generated from the parser and the keys' documentation (`solver/scene/scene_keys.cpp`) by "
      "`bash scripts/scene-keys.sh`, which runs `dustlift info --keys` over the repository's "
      "scenes; a test fails when this file is stale. Do not edit it by hand.\n";
  std::string section;
  std::vector<std::string> undocumented;
  for (const auto& [key, fact] : facts)
    if (find_key_doc(key) == nullptr) undocumented.push_back(key);
  for (const SceneKeyDoc& d : kDocs) {
    // The keys of this pattern that the scenes read, each with its facts written for the pattern.
    std::vector<std::pair<std::string, KeyFact>> rows;
    for (const auto& [key, f] : facts)
      if (matches(d.pattern, key) && find_key_doc(key) == &d && !f.kind.empty())
        rows.emplace_back(key, generic_fact(f, d.pattern, key));
    if (rows.empty()) continue;
    // One row for the pattern when its keys agree; else one per key (grid.x.start is required,
    // grid.y.start may follow the layer's thickness).
    const bool agree = std::all_of(rows.begin(), rows.end(), [&](const auto& r) {
      return same_fact(r.second, rows.front().second);
    });
    if (agree) {
      rows.resize(1);
      rows.front().first = std::string(d.pattern);
    } else {
      for (auto& [key, f] : rows) f = facts.at(key);
    }
    const std::string pattern(d.pattern);
    const std::string top = pattern.substr(0, pattern.find('.'));
    if (top != section) {
      section = top;
      out += fmt::format(
          "\n## {}\n\n| key | type | unit | default | allowed | meaning "
          "|\n|---|---|---|---|---|---|\n",
          section_title(section));
    }
    for (const auto& [key, fact] : rows)
      out +=
          fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", key, cell(fact.kind),
                      cell(std::string(d.unit)), cell(fact.fallback),
                      cell(fact.range == "finite" ? "" : fact.range), cell(std::string(d.meaning)));
  }
  if (!undocumented.empty()) {
    out += "\n## Undocumented\n\n";
    for (const auto& k : undocumented) out += "- `" + k + "`\n";
  }
  return out;
}

}  // namespace dustlift
