// [run], [grid], [output] and cross-section checks.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "solver/scene/parse_sections.hpp"
#include "solver/scene/resource_limits.hpp"

namespace dustlift::scene_detail {

void parse_run(TableReader t, RunConfig& run) {
  t.expect_keys({"name", "end_time", "max_steps", "progress_interval", "skip_at_rest",
                 "rest_tolerance", "rebalance_steps", "allow_implausible"});
  run.name = t.string("name", run.name);
  run.end_time = t.required_number("end_time", Range::positive());
  run.max_steps = t.integer("max_steps", 0, 0, 1'000'000'000'000LL);
  run.progress_interval =
      t.number("progress_interval", run.progress_interval, Range::non_negative());
  run.skip_at_rest = t.boolean("skip_at_rest", run.skip_at_rest);
  run.rest_tolerance = t.number("rest_tolerance", run.rest_tolerance, Range::closed(0.0, 1e-6));
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

}  // namespace

void parse_output(TableReader t, OutputConfig& out, const RunConfig& run, const DemConfig& dem,
                  const GridConfig& grid) {
  t.expect_keys({"interval", "vtk", "shock_threshold", "checkpoint_interval",
                 "checkpoint_wall_interval", "surface_threshold", "surface_stations",
                 "band_bin_width", "band_duration", "contact_window", "bands", "probes",
                 "probe_interval", "parcel_fronts", "dust_cloud", "cloud_lift_height",
                 "explosible_concentration", "cloud_edge_concentration"});
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
          "contact_window", "bands", "parcel_fronts", "dust_cloud", "cloud_lift_height",
          "explosible_concentration", "cloud_edge_concentration"}) {
      if (t.has(key)) t.fail(key, "only used with [particles]");
    }
    t.finish();
    return;
  }
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
  out.dust_cloud = t.boolean("dust_cloud", out.dust_cloud);
  if (!out.dust_cloud) {
    for (const char* key :
         {"cloud_lift_height", "explosible_concentration", "cloud_edge_concentration"})
      if (t.has(key)) t.fail(key, "only used with dust_cloud = true");
  } else {
    out.cloud_lift_height =
        t.derived_number("cloud_lift_height", dem.particle_diameter,
                         "particles.diameter (one particle diameter)", Range::non_negative());
    out.explosible_concentration =
        t.number("explosible_concentration", out.explosible_concentration, Range::positive());
    out.cloud_edge_concentration =
        t.number("cloud_edge_concentration", out.cloud_edge_concentration, Range::positive());
  }
  t.finish();
}

}  // namespace dustlift::scene_detail
