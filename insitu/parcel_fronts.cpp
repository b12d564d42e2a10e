#include "insitu/parcel_fronts.hpp"

#include <algorithm>
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

}  // namespace dustlift
