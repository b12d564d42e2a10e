#include "solver/sim/layer_resolution.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace dustlift {

double cells_across(const Axis& y, double bottom, double top) {
  if (!(top > bottom)) return 0.0;
  double widest = 0.0;
  for (int j = 0; j < y.cells(); ++j) {
    if (y.face(j + 1) > bottom && y.face(j) < top) widest = std::max(widest, y.width(j));
  }
  return widest > 0.0 ? (top - bottom) / widest : 0.0;
}

std::string layer_resolution_warning(const Axis& y, double bottom, double top) {
  const double cells = cells_across(y, bottom, top);
  if (cells <= 0.0 || cells >= kMinCellsAcrossLayer) return {};
  return fmt::format(
      "under-resolved: {:.3g} cell(s) of {:.3g} mm span the {:.3g} mm layer; the lifted mass, the "
      "cloud's height and its explosible mass change with the cells until {:g} or more span it "
      "(docs/dust-cloud.md, \"Why the cells matter\")",
      cells, (top - bottom) / cells * 1e3, (top - bottom) * 1e3, kMinCellsAcrossLayer);
}

}  // namespace dustlift
