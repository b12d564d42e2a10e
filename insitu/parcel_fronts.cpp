#include "insitu/parcel_fronts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace dustlift {

ParcelFronts parcel_fronts(std::span<const double> x, std::span<const double> weight, double share,
                           std::vector<std::size_t>& order) {
  const std::size_t n = x.size();
  if (n == 0 || weight.size() != n)
    throw std::invalid_argument("parcel_fronts: no parcels, or weights of another count");
  if (!(share > 0.0 && share < 0.5))
    throw std::invalid_argument("parcel_fronts: share must lie in (0, 0.5)");
  order.resize(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  // By x, ties by index: the same parcels in any order give the same fronts.
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return x[a] < x[b] || (x[a] == x[b] && a < b); });
  double total = 0.0;
  for (std::size_t k : order) total += weight[k];
  ParcelFronts f;
  f.x_min = x[order.front()];
  f.x_max = x[order.back()];
  const double low = share * total, high = (1.0 - share) * total;
  double sum = 0.0;
  bool have_low = false;
  f.x_high = f.x_max;
  for (std::size_t k : order) {
    sum += weight[k];
    if (!have_low && sum >= low) {
      f.x_low = x[k];
      have_low = true;
    }
    if (sum >= high) {
      f.x_high = x[k];
      break;
    }
  }
  return f;
}

void line_of_sight_profile(std::span<const double> x, std::span<const double> n_real,
                           std::span<const double> diameter, const LineOfSight& sight,
                           SightProfile& profile) {
  const std::size_t n = x.size();
  if (n_real.size() != n || diameter.size() != n)
    throw std::invalid_argument("line_of_sight_profile: columns of different counts");
  if (!(sight.bin > 0.0 && sight.height > 0.0 && sight.depth > 0.0))
    throw std::invalid_argument("line_of_sight_profile: bin, height and depth must be > 0");
  profile.tau.clear();
  if (n == 0) return;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  profile.first = std::floor(*lo / sight.bin);
  const auto bins = static_cast<std::size_t>(std::floor(*hi / sight.bin) - profile.first) + 1;
  profile.tau.assign(bins, 0.0);
  const double per_area = sight.depth / (sight.bin * sight.height);
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = static_cast<std::size_t>(std::floor(x[k] / sight.bin) - profile.first);
    profile.tau[b] += n_real[k] * 0.25 * std::numbers::pi * diameter[k] * diameter[k] * per_area;
  }
}

SightEdges sight_edges(const SightProfile& profile, const LineOfSight& sight) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double>& tau = profile.tau;
  const std::size_t bins = tau.size();
  const double t = sight.optical_depth;
  const auto centre = [&](std::size_t b) {
    return (profile.first + static_cast<double>(b) + 0.5) * sight.bin;
  };
  SightEdges e{nan, nan};
  // Upstream: the first bin reaching the threshold, the crossing between it and the bin before.
  for (std::size_t b = 0; b < bins; ++b) {
    if (tau[b] < t) continue;
    const double before = b > 0 ? tau[b - 1] : 0.0;
    e.upstream = centre(b) - sight.bin * (tau[b] - t) / (tau[b] - before);
    break;
  }
  for (std::size_t b = bins; b-- > 0;) {
    if (tau[b] < t) continue;
    const double after = b + 1 < bins ? tau[b + 1] : 0.0;
    e.downstream = centre(b) + sight.bin * (tau[b] - t) / (tau[b] - after);
    break;
  }
  return e;
}

SightEdges line_of_sight_edges(std::span<const double> x, std::span<const double> n_real,
                               std::span<const double> diameter, const LineOfSight& sight,
                               SightProfile& profile) {
  line_of_sight_profile(x, n_real, diameter, sight, profile);
  return sight_edges(profile, sight);
}

}  // namespace dustlift
