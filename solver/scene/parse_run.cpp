// [run], [grid], [output] and cross-section checks.
#include "solver/scene/parse_sections.hpp"

#include <algorithm>
#include <stdexcept>

namespace dustlift::scene_detail {

void parse_run(TableReader t, RunConfig& run) {
  run.name = t.string("name", run.name);
  run.end_time = t.required_number("end_time", Range::positive());
  run.max_steps = t.integer("max_steps", 0, 0, 1'000'000'000'000LL);
  run.progress_interval = t.number("progress_interval", run.progress_interval, Range::non_negative());
  run.skip_at_rest = t.boolean("skip_at_rest", run.skip_at_rest);
  t.finish();
}

static AxisSpec parse_axis(TableReader t) {
  AxisSpec a;
  a.start = t.required_number("start");
  a.end = t.required_number("end");
  if (!(a.end > a.start)) t.fail("end", "must be greater than start");
  if (t.has("cell_size")) {
    a.cell_size = t.required_number("cell_size", Range::positive());
    a.uniform_start = t.number("uniform_start", a.start);
    a.uniform_end = t.number("uniform_end", a.end);
    a.cells_below = static_cast<std::size_t>(t.integer("cells_below", 0, 0, 100'000'000));
    a.cells_above = static_cast<std::size_t>(t.integer("cells_above", 0, 0, 100'000'000));
    if (t.has("cells")) t.fail("cells", "give either cells (uniform axis) or cell_size (uniform core with stretched ends), not both");
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

void parse_grid(TableReader t, GridConfig& grid) {
  grid.x = parse_axis(t.table("x", true));
  grid.y = parse_axis(t.table("y", true));
  t.finish();
}

double min_cell_width(const GridConfig& grid) {
  return std::min(Axis(build_axis_nodes(grid.x), 0).min_width(), Axis(build_axis_nodes(grid.y), 0).min_width());
}

void parse_output(TableReader t, OutputConfig& out, const RunConfig& run, const DemConfig& dem) {
  out.interval = t.number("interval", out.interval, Range::non_negative());
  out.vtk = t.boolean("vtk", out.vtk);
  out.shock_threshold = t.number("shock_threshold", out.shock_threshold, Range::open(0.0, 10.0));
  out.checkpoint_interval = t.number("checkpoint_interval", out.interval, Range::non_negative());
  out.checkpoint_wall_interval = t.number("checkpoint_wall_interval", out.checkpoint_wall_interval, Range::non_negative());
  if (!dem.enabled) {
    t.finish();
    return;
  }
  const LayerConfig& L = dem.layer;
  out.surface_threshold = t.number("surface_threshold", out.surface_threshold, Range::open(0.0, 1.0));
  // Default stations: a quarter, half and three quarters along the layer.
  const double len = L.x_max - L.x_min;
  out.surface_stations = t.number_list("surface_stations", {L.x_min + 0.25 * len, L.x_min + 0.5 * len, L.x_min + 0.75 * len});
  out.band_bin_width = t.number("band_bin_width", out.band_bin_width, Range::positive());
  out.band_duration = t.number("band_duration", run.end_time, Range::positive());
  out.contact_window = t.number("contact_window", out.contact_window, Range::positive());
  auto bands = t.table_array("bands");
  if (bands.empty()) {
    // The paper's bands (section 3.4), placed relative to the layer: x over the second
    // quarter of the layer (100-200 mm of 400 mm), the top 0.1 mm and 0.1 mm around mid-depth.
    const double top = L.y_max, mid = 0.5 * (L.y_min + L.y_max);
    out.bands = {{"surface", L.x_min + 0.25 * len, L.x_min + 0.5 * len, top - 0.1e-3, top},
                 {"middle", L.x_min + 0.25 * len, L.x_min + 0.5 * len, mid - 0.1e-3, mid + 0.1e-3}};
  }
  for (auto& b : bands) {
    BandConfig c;
    c.name = b.string("name", "");
    if (c.name.empty() || c.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos) {
      b.fail("name", "a band needs a name of lower-case letters, digits and _ (it names the series file)");
    }
    c.x_min = b.required_number("x_min");
    c.x_max = b.required_number("x_max");
    c.y_min = b.required_number("y_min");
    c.y_max = b.required_number("y_max");
    if (!(c.x_max > c.x_min)) b.fail("x_max", "must be greater than x_min");
    if (!(c.y_max > c.y_min)) b.fail("y_max", "must be greater than y_min");
    b.finish();
    out.bands.push_back(c);
  }
  t.finish();
}

void check_cross_section(const Scene& s) {
  if (s.initial.kind != InitialCondition::Kind::Uniform) {
    const AxisSpec& a = s.initial.axis == 'x' ? s.grid.x : s.grid.y;
    if (s.initial.position <= a.start || s.initial.position >= a.end) {
      throw SceneError(s.source_file + ": key 'initial.position': " + std::to_string(s.initial.position) +
                       " lies outside the grid along " + s.initial.axis);
    }
  }
}

}  // namespace dustlift::scene_detail
