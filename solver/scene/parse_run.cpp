// [run], [grid], [output] and cross-section checks.
#include "solver/scene/parse_sections.hpp"

#include <stdexcept>

namespace dustlift::scene_detail {

void parse_run(TableReader t, RunConfig& run) {
  run.name = t.string("name", run.name);
  run.end_time = t.required_number("end_time", Range::positive());
  run.max_steps = t.integer("max_steps", 0, 0, 1'000'000'000'000LL);
  run.progress_interval = t.number("progress_interval", run.progress_interval, Range::non_negative());
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

void parse_output(TableReader t, OutputConfig& out) {
  out.interval = t.number("interval", out.interval, Range::non_negative());
  out.vtk = t.boolean("vtk", out.vtk);
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
