#include "insitu/lifting_delay.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace dustlift {

double lifting_delay_distance(std::span<const double> x_centers, std::span<const double> heights,
                              double shock_x, double layer_top, double layer_x_max,
                              double lift_threshold) {
  if (x_centers.size() != heights.size())
    throw std::invalid_argument("lifting_delay_distance: one height per column centre needed");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(shock_x) || shock_x > layer_x_max) return nan;
  const double level = layer_top + lift_threshold;
  // k: the column nearest behind the shock still below the level (NaN columns have no dust
  // and neither start nor interrupt a rise).
  std::size_t below = x_centers.size();
  for (std::size_t k = x_centers.size(); k-- > 0;) {
    if (x_centers[k] > shock_x || std::isnan(heights[k])) continue;
    if (heights[k] > level) {
      if (below == x_centers.size()) return shock_x - x_centers[k];  // lifted right at the shock
      const double s = (level - heights[below]) / (heights[k] - heights[below]);
      return shock_x - (x_centers[below] + s * (x_centers[k] - x_centers[below]));
    }
    below = k;
  }
  return nan;
}

}  // namespace dustlift
