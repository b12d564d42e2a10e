#pragma once
// Whether the cells resolve the dust layer's depth. With one cell across the layer, the gas
// over it (slowed by the layer's drag, its pressure lagging behind the gas above) is resolved
// over that one cell, and the lifted mass, the cloud's height and its explosible mass change by
// tens of per cent when the cells are halved; from two cells across on, by a few per cent
// (docs/dust-cloud.md, "Why the cells matter").
#include <string>

#include "solver/core/grid.hpp"

namespace dustlift {

/// The fewest cells to span a layer's depth before its cloud stops depending on them at the
/// level of a few per cent (docs/dust-cloud.md: 1 -> 2 cells moved the explosible mass by
/// 14-51 %, 2 -> 4 cells by 5 %).
inline constexpr double kMinCellsAcrossLayer = 2.0;

/// How many cells of axis `y` span [bottom, top]: the depth over the widest cell it overlaps
/// (0 when the interval lies outside the axis or is empty).
double cells_across(const Axis& y, double bottom, double top);

/// The line `info` and the run's log give when fewer than kMinCellsAcrossLayer cells span
/// the layer [bottom, top]; empty otherwise.
std::string layer_resolution_warning(const Axis& y, double bottom, double top);

}  // namespace dustlift
