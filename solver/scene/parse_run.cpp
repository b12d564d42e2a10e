// [run], [grid], [output] and cross-section checks.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "solver/scene/cloud_filter.hpp"
#include "solver/scene/parse_sections.hpp"
#include "solver/scene/resource_limits.hpp"

namespace dustlift::scene_detail {

void parse_run(TableReader t, RunConfig& run) {
  t.expect_keys({"name", "end_time", "max_steps", "progress_interval", "skip_at_rest", "exact",
                 "rest_tolerance", "rebalance_steps", "allow_implausible"});
  run.name = t.string("name", run.name);
  run.end_time = t.required_number("end_time", Range::positive());
  run.max_steps = t.integer("max_steps", 0, 0, 1'000'000'000'000LL);
  run.progress_interval =
      t.number("progress_interval", run.progress_interval, Range::non_negative());
  run.skip_at_rest = t.boolean("skip_at_rest", run.skip_at_rest);
  run.exact = t.boolean("exact", run.exact);
  // The default tolerance holds only while skipping within one: exact skipping and no
  // skipping derive 0 (so the resolved scene runs again as it is).
  const bool within = run.skip_at_rest && !run.exact;
  run.rest_tolerance = t.derived_number(
      "rest_tolerance", within ? run.rest_tolerance : 0.0,
      fmt::format("run.exact and run.skip_at_rest: {:g} when skipping, 0 when exact or not",
                  run.rest_tolerance),
      Range::closed(0.0, 1e-6));
  if (run.rest_tolerance > 0.0 && run.exact)
    t.fail("exact", "= true skips only what rests exactly: leave run.rest_tolerance out or 0");
  if (run.rest_tolerance > 0.0 && !run.skip_at_rest)
    t.fail("rest_tolerance",
           "needs skip_at_rest = true (it widens what skipping counts as at rest)");
  run.rebalance_steps = t.integer("rebalance_steps", run.rebalance_steps, 0, 1'000'000'000'000LL);
  run.allow_implausible = t.boolean("allow_implausible", run.allow_implausible);
  t.finish();
}

/// One axis. The y axis (`vertical`) starts at the floor, which follows `floor` (a scene with
/// particles.layer.thickness) unless grid.y.start is given.
static AxisSpec parse_axis(TableReader t, bool vertical,
                           const std::optional<LayerFloor>& floor = std::nullopt) {
  t.expect_keys({"start", "end", "cells", "cell_size", "uniform_start", "uniform_end",
                 "cells_below", "cells_above"});
  AxisSpec a;
  if (vertical && !floor && !t.has("start"))
    t.fail("start",
           "missing: give grid.y.start (the floor, m), or particles.layer.thickness (the floor is "
           "then "
           "the layer's bottom)");
  if (floor) {
    a.start = t.derived_number(
        "start", floor->y,
        "particles.layer.thickness (the floor is the layer's bottom, y_max - thickness)");
    if (t.has("start") && !agrees_with_floor(a.start, *floor))
      t.fail(
          "start",
          fmt::format(
              "{:.9g} m contradicts particles.layer.thickness = {:.9g} m: the floor is the layer's "
              "bottom, particles.layer.y_max - thickness = {:.9g} m; leave grid.y.start out (it "
              "follows the thickness) or give particles.layer.y_min instead of the thickness",
              a.start, floor->thickness, floor->y));
  } else {
    a.start = t.required_number("start");
  }
  a.end = t.required_number("end");
  if (!(a.end > a.start)) t.fail("end", "must be greater than start");
  if (t.has("cell_size")) {
    a.cell_size = t.required_number("cell_size", Range::positive());
    a.uniform_start = t.derived_number("uniform_start", a.start, t.full_key("start"));
    a.uniform_end = t.derived_number("uniform_end", a.end, t.full_key("end"));
    a.cells_below = static_cast<std::size_t>(t.integer("cells_below", 0, 0, 100'000'000));
    a.cells_above = static_cast<std::size_t>(t.integer("cells_above", 0, 0, 100'000'000));
    if (t.has("cells"))
      t.fail("cells",
             "give either cells (uniform axis) or cell_size (uniform core with stretched ends), "
             "not both");
  } else {
    a.cells = static_cast<std::size_t>(t.integer("cells", 0, 1, 100'000'000));
    if (!t.has("cells")) t.fail("cells", "missing: give cells (uniform axis) or cell_size");
  }
  try {
    (void)build_axis_nodes(a);
  } catch (const std::invalid_argument& e) {
    t.fail(t.has("cell_size") ? "cell_size" : "cells", e.what());
  }
  t.finish();
  return a;
}

void parse_grid(TableReader t, GridConfig& grid, const std::optional<LayerFloor>& floor) {
  t.expect_keys({"x", "y"});
  TableReader tx = t.table("x", true), ty = t.table("y", true);
  grid.x = parse_axis(tx, false);
  grid.y = parse_axis(ty, true, floor);
  // Before anything is allocated: the whole grid must fit the machine.
  const std::size_t nx = build_axis_nodes(grid.x).size() - 1,
                    ny = build_axis_nodes(grid.y).size() - 1;
  const double cells = static_cast<double>(nx) * static_cast<double>(ny);
  if (const std::string shortfall = memory_shortfall(cells, 0.0); !shortfall.empty()) {
    TableReader& larger = nx >= ny ? tx : ty;
    const AxisSpec& axis = nx >= ny ? grid.x : grid.y;
    larger.fail(axis.cell_size > 0.0 ? "cell_size" : "cells",
                fmt::format("{} x {} = {:.3g} cells: the run {}", nx, ny, cells, shortfall));
  }
  t.finish();
}

double min_cell_width(const GridConfig& grid) {
  return std::min(Axis(build_axis_nodes(grid.x), 0).min_width(),
                  Axis(build_axis_nodes(grid.y), 0).min_width());
}

namespace {

/// A name that names a series or column: lower-case letters, digits and _.
void check_series_name(TableReader& t, const std::string& name, const char* what) {
  if (name.empty() ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos) {
    t.fail("name", std::string("a ") + what +
                       " needs a name of lower-case letters, digits and _ (it names its series)");
  }
}

void parse_bands(TableReader& t, OutputConfig& out, const LayerConfig& L) {
  auto bands = t.table_array("bands");
  if (bands.empty()) {
    // The paper's bands (section 3.4), placed relative to the layer: x over the second
    // quarter of the layer (100-200 mm of 400 mm), the top 0.1 mm and 0.1 mm around mid-depth.
    const double len = L.x_max - L.x_min, top = L.y_max, mid = 0.5 * (L.y_min + L.y_max);
    out.bands = {{"surface", L.x_min + 0.25 * len, L.x_min + 0.5 * len, top - 0.1e-3, top},
                 {"middle", L.x_min + 0.25 * len, L.x_min + 0.5 * len, mid - 0.1e-3, mid + 0.1e-3}};
    std::string text;
    for (const BandConfig& b : out.bands) {
      text += fmt::format("{}{{ name = \"{}\", x_min = {}, x_max = {}, y_min = {}, y_max = {} }}",
                          text.empty() ? "[" : ", ", b.name, b.x_min, b.x_max, b.y_min, b.y_max);
    }
    t.note_derived("bands", text + "]", "particles.layer (the paper's bands: section 3.4)");
    return;
  }
  for (auto& b : bands) {
    b.expect_keys({"name", "x_min", "x_max", "y_min", "y_max"});
    BandConfig c;
    c.name = b.string("name", "");
    check_series_name(b, c.name, "band");
    c.x_min = b.required_number("x_min");
    c.x_max = b.required_number("x_max");
    c.y_min = b.required_number("y_min");
    c.y_max = b.required_number("y_max");
    if (!(c.x_max > c.x_min)) b.fail("x_max", "must be greater than x_min");
    if (!(c.y_max > c.y_min)) b.fail("y_max", "must be greater than y_min");
    b.finish();
    out.bands.push_back(c);
  }
}

void parse_probes(TableReader& t, OutputConfig& out, const GridConfig& grid, bool particles) {
  out.probe_interval = t.number("probe_interval", out.probe_interval, Range::non_negative());
  for (auto& p : t.table_array("probes")) {
    p.expect_keys({"name", "x", "y", "fields"});
    ProbeConfig c;
    c.name = p.string("name", "");
    check_series_name(p, c.name, "probe");
    for (const ProbeConfig& other : out.probes) {
      if (other.name == c.name) p.fail("name", "\"" + c.name + "\" names another probe too");
    }
    c.x = p.required_number(
        "x", Range::closed(grid.x.start, grid.x.end).named("in [grid.x.start, grid.x.end]"));
    c.y = p.required_number(
        "y", Range::closed(grid.y.start, grid.y.end).named("in [grid.y.start, grid.y.end]"));
    std::vector<std::string> fields;
    for (const ProbeField& f : kProbeFields) {
      if (std::string(f.name) != "mach" && (particles || std::string(f.name) != "alpha_p"))
        fields.emplace_back(f.name);
    }
    c.fields = p.string_list("fields", fields);
    std::string allowed;
    for (const ProbeField& k : kProbeFields)
      allowed += (allowed.empty() ? "\"" : ", \"") + std::string(k.name) + "\"";
    if (KeyFact* f = p.recorded_fact("fields")) f->range = "each one of " + allowed;
    for (const std::string& f : c.fields) {
      const bool known = std::any_of(std::begin(kProbeFields), std::end(kProbeFields),
                                     [&](const ProbeField& k) { return f == k.name; });
      if (!known) p.fail("fields", "\"" + f + "\" is not one of " + allowed);
    }
    if (c.fields.empty()) p.fail("fields", "a probe needs at least one field");
    p.finish();
    out.probes.push_back(c);
  }
}

/// [output.line_of_sight]: how the parcel_fronts series sees the cloud through the channel.
void parse_line_of_sight(TableReader& t, OutputConfig& out, const GridConfig& grid) {
  TableReader s = t.table("line_of_sight");
  s.expect_keys({"depth", "optical_depth", "bin"});
  if (!out.parcel_fronts) {
    if (s.present()) s.fail("depth", "only used with output.parcel_fronts = true");
    return;
  }
  OutputConfig::LineOfSight& l = out.line_of_sight;
  l.depth = s.derived_number("depth", grid.y.end - grid.y.start,
                             "grid.y (the channel height: a square channel)", Range::positive());
  l.optical_depth = s.number("optical_depth", l.optical_depth, Range::positive());
  l.bin = s.derived_number("bin", min_cell_width(grid), "grid (the smallest cell width)",
                           Range::positive());
  s.finish();
}

void parse_dust_cloud(TableReader& t, OutputConfig& out, const DemConfig& dem,
                      const GridConfig& grid) {
  const LayerConfig& L = dem.layer;
  out.cloud_lift_height =
      t.derived_number("cloud_lift_height", dem.particle_diameter,
                       "particles.diameter (one particle diameter)", Range::non_negative());
  out.cloud_top_concentration =
      t.number("cloud_top_concentration", out.cloud_top_concentration, Range::positive());
  out.explosible_lower = t.number("explosible_lower", out.explosible_lower, Range::positive());
  out.explosible_upper = t.number("explosible_upper", out.explosible_upper, Range::positive());
  if (!(out.explosible_upper > out.explosible_lower))
    t.fail("explosible_upper",
           fmt::format("{:g} kg/m^3 must be greater than explosible_lower ({:g} kg/m^3): the "
                       "explosible band is [explosible_lower, explosible_upper]",
                       out.explosible_upper, out.explosible_lower));
  // The channel above the layer: the filter's cells and the heights live there.
  const double room = grid.y.end - L.y_max;
  const double mass = largest_parcel_mass(dem);
  out.cloud_filter_width = t.derived_number(
      "cloud_filter_width", default_cloud_filter_width(mass, out.explosible_lower, room),
      "the largest parcel's mass: one parcel alone in a box is a tenth of explosible_lower, "
      "at most the channel's height above the layer",
      Range::positive());
  out.fines_diameter = t.number("fines_diameter", out.fines_diameter, Range::positive());
  std::vector<double> heights;
  for (double h : {1e-3, 2e-3, 5e-3})
    if (h < room) heights.push_back(h);
  out.entrainment_heights = t.derived_number_list(
      "entrainment_heights", heights, "1, 2 and 5 mm above the layer top, those inside the channel",
      Range::positive());
  for (std::size_t k = 0; k < out.entrainment_heights.size(); ++k) {
    const double h = out.entrainment_heights[k];
    if (!(h < room))
      t.fail("entrainment_heights",
             fmt::format("{:g} m is not inside the channel: heights count from the layer top "
                         "(particles.layer.y_max) and must be below the {:g} m above it",
                         h, room));
    if (k > 0 && !(h > out.entrainment_heights[k - 1]))
      t.fail("entrainment_heights", "the heights must increase");
  }
  if (out.entrainment_heights.size() > 16) t.fail("entrainment_heights", "at most 16 heights");
  out.entrainment_bin_width =
      t.derived_number("entrainment_bin_width", (L.x_max - L.x_min) / 40.0,
                       "particles.layer (a fortieth of its length)", Range::positive());
}

/// Replaced keys, in g/m^3 (the only keys not in SI units): refused, naming what replaces
/// them, since the new keys would read the old values 1000 times too large.
void refuse_replaced_output_keys(const TableReader& t) {
  if (t.has("explosible_concentration"))
    t.fail("explosible_concentration",
           "is replaced by explosible_lower and explosible_upper, the explosible band of the "
           "filtered dust concentration in kg/m^3 (SI): 50 g/m^3 is explosible_lower = 0.05");
  if (t.has("cloud_edge_concentration"))
    t.fail("cloud_edge_concentration",
           "is replaced by cloud_top_concentration in kg/m^3 (SI): 1 g/m^3 is "
           "cloud_top_concentration = 0.001");
}

/// The outputs of the dust: the surface, the bands, the parcel fronts, the line of sight and
/// the dust cloud.
void parse_dust_outputs(TableReader& t, OutputConfig& out, const RunConfig& run,
                        const DemConfig& dem, const GridConfig& grid) {
  const LayerConfig& L = dem.layer;
  out.surface_threshold =
      t.number("surface_threshold", out.surface_threshold, Range::open(0.0, 1.0));
  // Default stations: a quarter, half and three quarters along the layer.
  const double len = L.x_max - L.x_min;
  out.surface_stations = t.derived_number_list(
      "surface_stations", {L.x_min + 0.25 * len, L.x_min + 0.5 * len, L.x_min + 0.75 * len},
      "particles.layer (a quarter, half and three quarters along it)");
  out.band_bin_width = t.number("band_bin_width", out.band_bin_width, Range::positive());
  out.band_duration =
      t.derived_number("band_duration", run.end_time, "run.end_time", Range::positive());
  out.contact_window = t.number("contact_window", out.contact_window, Range::positive());
  parse_bands(t, out, L);
  out.parcel_fronts = t.boolean("parcel_fronts", out.parcel_fronts);
  parse_line_of_sight(t, out, grid);
  out.dust_cloud = t.boolean("dust_cloud", out.dust_cloud);
  if (!out.dust_cloud) {
    for (const char* key :
         {"cloud_lift_height", "cloud_top_concentration", "cloud_filter_width", "explosible_lower",
          "explosible_upper", "fines_diameter", "entrainment_heights", "entrainment_bin_width"})
      if (t.has(key)) t.fail(key, "only used with dust_cloud = true");
  } else {
    parse_dust_cloud(t, out, dem, grid);
  }
}

}  // namespace

void parse_output(TableReader t, OutputConfig& out, const RunConfig& run, const DemConfig& dem,
                  const GridConfig& grid) {
  refuse_replaced_output_keys(t);
  t.expect_keys({"interval",
                 "vtk",
                 "shock_threshold",
                 "checkpoint_interval",
                 "checkpoint_wall_interval",
                 "surface_threshold",
                 "surface_stations",
                 "band_bin_width",
                 "band_duration",
                 "contact_window",
                 "bands",
                 "probes",
                 "probe_interval",
                 "parcel_fronts",
                 "line_of_sight",
                 "dust_cloud",
                 "cloud_lift_height",
                 "cloud_top_concentration",
                 "cloud_filter_width",
                 "explosible_lower",
                 "explosible_upper",
                 "fines_diameter",
                 "entrainment_heights",
                 "entrainment_bin_width"});
  out.interval = t.number("interval", out.interval, Range::non_negative());
  out.vtk = t.boolean("vtk", out.vtk);
  out.shock_threshold = t.number("shock_threshold", out.shock_threshold, Range::open(0.0, 10.0));
  out.checkpoint_interval = t.derived_number("checkpoint_interval", out.interval, "output.interval",
                                             Range::non_negative());
  out.checkpoint_wall_interval =
      t.number("checkpoint_wall_interval", out.checkpoint_wall_interval, Range::non_negative());
  parse_probes(t, out, grid, dem.enabled);
  if (!dem.enabled) {
    // Dust switched off on purpose (particles.enabled = false): its output keys stay unread.
    if (dem.switched_off) return;
    for (const char* key :
         {"surface_threshold", "surface_stations", "band_bin_width", "band_duration",
          "contact_window", "bands", "parcel_fronts", "line_of_sight", "dust_cloud",
          "cloud_lift_height", "cloud_top_concentration", "cloud_filter_width", "explosible_lower",
          "explosible_upper", "fines_diameter", "entrainment_heights", "entrainment_bin_width"}) {
      if (t.has(key)) t.fail(key, "only used with [particles]");
    }
    t.finish();
    return;
  }
  parse_dust_outputs(t, out, run, dem, grid);
  t.finish();
}

}  // namespace dustlift::scene_detail
