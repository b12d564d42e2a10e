#include "insitu/surface_height.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace dustlift {

std::vector<double> dust_surface_height(std::span<const double> y_faces,
                                        std::span<const double> alpha_p, std::size_t nx,
                                        double threshold) {
  if (y_faces.size() < 2)
    throw std::invalid_argument("dust_surface_height: at least one cell (two faces) needed");
  const std::size_t ny = y_faces.size() - 1;
  if (alpha_p.size() != nx * ny)
    throw std::invalid_argument("dust_surface_height: alpha_p must hold nx*ny values");
  std::vector<double> h(nx, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < nx; ++i) {
    for (std::size_t j = ny; j-- > 0;) {  // from the top down: the highest cell wins
      const double a = alpha_p[i + nx * j];
      if (!(a > threshold)) continue;
      const double below = j > 0 ? alpha_p[i + nx * (j - 1)] : a;
      const double fill = a / std::max(a, below);  // in (0, 1]
      h[i] = y_faces[j] + fill * (y_faces[j + 1] - y_faces[j]);
      break;
    }
  }
  return h;
}

double height_at_station(std::span<const double> x_centers, std::span<const double> heights,
                         double station_x) {
  const std::size_t n = x_centers.size();
  if (heights.size() != n || n == 0)
    throw std::invalid_argument("height_at_station: one height per column centre needed");
  if (n == 1 || station_x <= x_centers.front()) return heights.front();
  if (station_x >= x_centers.back()) return heights.back();
  const auto upper = std::upper_bound(x_centers.begin(), x_centers.end(), station_x);
  const std::size_t k = static_cast<std::size_t>(upper - x_centers.begin());  // 1..n-1
  const double s = (station_x - x_centers[k - 1]) / (x_centers[k] - x_centers[k - 1]);
  return heights[k - 1] + s * (heights[k] - heights[k - 1]);  // NaN propagates
}

}  // namespace dustlift
