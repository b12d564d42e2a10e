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

double shock_position(std::span<const double> x_centers, std::span<const double> y_centers,
                      std::span<const double> pressure, double p_ambient, double threshold,
                      double y_min) {
  const std::size_t nx = x_centers.size(), ny = y_centers.size();
  if (pressure.size() != nx * ny) throw std::invalid_argument("shock_position: size mismatch");
  double best = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t j = 0; j < ny; ++j) {
    if (y_centers[j] < y_min) continue;
    const double x =
        shock_position_on_row(x_centers, pressure.subspan(j * nx, nx), p_ambient, threshold);
    if (!std::isnan(x) && (std::isnan(best) || x > best)) best = x;
  }
  return best;
}

}  // namespace dustlift
