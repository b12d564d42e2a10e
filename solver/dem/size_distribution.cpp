// Size classes, class counts and their assignment to the layer's parcels.
#include "solver/dem/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <stdexcept>

namespace dustlift {

double standard_normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0))
    throw std::invalid_argument("standard_normal_quantile: p must lie in (0, 1)");
  if (p == 0.5) return 0.0;
  // Solve Phi(x) = q for q = min(p, 1 - p) <= 1/2 on x <= 0, where Phi is increasing and
  // convex: Newton from x = 0 stays right of the root and converges monotonically.
  const bool upper = p > 0.5;
  const double q = upper ? 1.0 - p : p;
  const double inv_sqrt2 = 1.0 / std::numbers::sqrt2;
  const double inv_sqrt_2pi = 0.5 * std::numbers::inv_sqrtpi * std::numbers::sqrt2;
  double x = 0.0;
  for (int it = 0; it < 200; ++it) {
    const double phi = 0.5 * std::erfc(-x * inv_sqrt2);
    const double density = inv_sqrt_2pi * std::exp(-0.5 * x * x);
    const double step = (phi - q) / density;
    x -= step;
    if (std::fabs(step) <= 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(x)) break;
  }
  return upper ? -x : x;
}

std::vector<SizeClass> lognormal_classes(double median, double geometric_std, int classes) {
  if (!(median > 0.0) || !(geometric_std > 1.0) || classes < 1)
    throw std::invalid_argument("lognormal_classes: needs median > 0, sigma_g > 1, classes >= 1");
  std::vector<SizeClass> out(static_cast<std::size_t>(classes));
  const double ln_sigma = std::log(geometric_std);
  for (int k = 0; k < classes; ++k) {
    const double p = (k + 0.5) / classes;
    out[static_cast<std::size_t>(k)] = {median * std::exp(ln_sigma * standard_normal_quantile(p)),
                                        1.0 / classes};
  }
  return out;
}

double mass_median_diameter(const std::vector<SizeClass>& classes) {
  double cumulative = 0.0;
  for (const SizeClass& c : classes) {
    cumulative += c.mass_fraction;
    if (cumulative >= 0.5 * (1.0 - 1e-12)) return c.diameter;
  }
  return classes.empty() ? 0.0 : classes.back().diameter;
}

std::vector<std::int64_t> largest_remainder_counts(std::int64_t total,
                                                   const std::vector<double>& fractions) {
  const std::size_t n = fractions.size();
  std::vector<std::int64_t> counts(n, 0);
  std::vector<double> remainder(n, 0.0);
  std::int64_t given = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double share = static_cast<double>(total) * fractions[k];
    counts[k] = static_cast<std::int64_t>(std::floor(share));
    remainder[k] = share - static_cast<double>(counts[k]);
    given += counts[k];
  }
  // The units left (fewer than n when the fractions sum to 1; the floors never exceed the
  // total while total times the fractions' excess over 1 stays below one) to the largest
  // remainders.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  for (std::size_t a = 0; a < n; ++a) {  // stable selection sort by remainder, descending
    std::size_t best = a;
    for (std::size_t b = a + 1; b < n; ++b)
      if (remainder[order[b]] > remainder[order[best]]) best = b;
    const std::size_t chosen = order[best];
    for (std::size_t b = best; b > a; --b) order[b] = order[b - 1];
    order[a] = chosen;
  }
  for (std::size_t r = 0; given < total && n > 0; r = (r + 1) % n, ++given) ++counts[order[r]];
  return counts;
}

namespace {

/// A uniform integer in [0, bound) from the generator's raw 64-bit output: values from the
/// incomplete last block of width `bound` are rejected, so every integer is equally likely.
std::uint64_t bounded(std::mt19937_64& g, std::uint64_t bound) {
  const std::uint64_t limit =
      std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % bound;
  std::uint64_t v = g();
  while (v >= limit) v = g();
  return v % bound;
}

}  // namespace

std::vector<int> shuffled_classes(const std::vector<std::int64_t>& counts, std::uint64_t seed) {
  std::vector<int> sites;
  for (std::size_t k = 0; k < counts.size(); ++k)
    sites.insert(sites.end(), static_cast<std::size_t>(counts[k]), static_cast<int>(k));
  std::mt19937_64 g(seed);  // its output sequence is fixed by the standard
  for (std::size_t i = sites.size(); i > 1; --i) {
    const auto j = static_cast<std::size_t>(bounded(g, i));
    std::swap(sites[i - 1], sites[j]);
  }
  return sites;
}

std::vector<SizeClass> file_size_classes(const std::vector<PlacedParcel>& parcels,
                                         double reference_d, double parcel_d) {
  std::vector<SizeClass> classes;
  bool any_given = false;
  for (const PlacedParcel& p : parcels) any_given = any_given || p.particle_diameter > 0.0;
  if (!any_given) return classes;
  std::vector<double> d;
  for (const PlacedParcel& p : parcels)
    d.push_back(p.particle_diameter > 0.0 ? p.particle_diameter : reference_d);
  std::sort(d.begin(), d.end());
  d.erase(std::unique(d.begin(), d.end()), d.end());
  for (double v : d) classes.push_back({v, 0.0});
  double total = 0.0;
  for (const PlacedParcel& p : parcels) {
    const double share = (p.diameter / parcel_d) * (p.diameter / parcel_d);
    const int k =
        size_class_of(classes, p.particle_diameter > 0.0 ? p.particle_diameter : reference_d);
    classes[static_cast<std::size_t>(k)].mass_fraction += share;
    total += share;
  }
  for (SizeClass& c : classes) c.mass_fraction /= total;
  return classes;
}

int size_class_of(const std::vector<SizeClass>& classes, double diameter) {
  const auto it = std::lower_bound(classes.begin(), classes.end(), diameter,
                                   [](const SizeClass& c, double d) { return c.diameter < d; });
  if (it == classes.end() || it->diameter != diameter) return -1;
  return static_cast<int>(it - classes.begin());
}

double same_volume_real_per_parcel(double n_ref, double d_ref, double d) {
  if (d == d_ref) return n_ref;
  const double r = d_ref / d;
  return n_ref * r * r * r;
}

}  // namespace dustlift
