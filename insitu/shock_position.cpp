#include "insitu/shock_position.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dustlift {

double shock_position_on_row(std::span<const double> x_centers, std::span<const double> p,
                             double p_ambient, double threshold) {
  const std::size_t n = x_centers.size();
  if (p.size() != n) throw std::invalid_argument("shock_position_on_row: size mismatch");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (n == 0) return nan;
  const double ambient = p_ambient > 0.0 ? p_ambient : p[n - 1];
  const double level = ambient * (1.0 + threshold);
  for (std::size_t i = n; i-- > 0;) {
    if (!(p[i] > level)) continue;
    // Raised up to the last cell: no undisturbed gas ahead, the shock has left the domain
    // (or not yet formed inside it); a position here would freeze at the last centre.
    if (i + 1 == n) return nan;
    const double s = (p[i] - level) / (p[i] - p[i + 1]);
    return x_centers[i] + s * (x_centers[i + 1] - x_centers[i]);
  }
  return nan;
}

namespace {

/// The furthest row's shock over the rows at or above y_min; row_of(j) gives row j's pressures.
template <class RowOf>
double furthest_row_shock(std::span<const double> x_centers, std::span<const double> y_centers,
                          RowOf row_of, double p_ambient, double threshold, double y_min) {
  // Every step, over the whole grid: the rows in parallel, whose maximum is the same whatever
  // order they come in.
  const auto rows = static_cast<std::ptrdiff_t>(y_centers.size());
  const double none = -std::numeric_limits<double>::infinity();
  double best = none;
#pragma omp parallel for schedule(static) \
    reduction(max                         \
              : best) if (y_centers.size() * x_centers.size() >= 32768)
  for (std::ptrdiff_t j = 0; j < rows; ++j) {
    const auto row = static_cast<std::size_t>(j);
    if (y_centers[row] < y_min) continue;
    const double x = shock_position_on_row(x_centers, row_of(row), p_ambient, threshold);
    if (!std::isnan(x)) best = std::max(best, x);
  }
  return best == none ? std::numeric_limits<double>::quiet_NaN() : best;
}

}  // namespace

double shock_position(std::span<const double> x_centers, std::span<const double> y_centers,
                      std::span<const double> pressure, double p_ambient, double threshold,
                      double y_min) {
  const std::size_t nx = x_centers.size(), ny = y_centers.size();
  if (pressure.size() != nx * ny) throw std::invalid_argument("shock_position: size mismatch");
  return furthest_row_shock(
      x_centers, y_centers, [&](std::size_t j) { return pressure.subspan(j * nx, nx); }, p_ambient,
      threshold, y_min);
}

double shock_position(const Grid2D& grid, const Field2D& pressure,
                      std::span<const double> x_centers, std::span<const double> y_centers,
                      double p_ambient, double threshold, double y_min) {
  const std::size_t nx = x_centers.size();
  if (nx != static_cast<std::size_t>(grid.nx()) ||
      y_centers.size() != static_cast<std::size_t>(grid.ny()) ||
      pressure.size() != grid.size_with_ghosts())
    throw std::invalid_argument("shock_position: the field or the centres do not fit the grid");
  return furthest_row_shock(
      x_centers, y_centers,
      [&](std::size_t j) {
        return std::span<const double>(pressure.data() + grid.index(0, static_cast<int>(j)), nx);
      },
      p_ambient, threshold, y_min);
}

}  // namespace dustlift
