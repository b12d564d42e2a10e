#pragma once
// Polydisperse layers (docs/dem.md, "Polydisperse layers"): the size classes of a
// log-normal distribution, the parcel count of each class and which parcel gets which
// class. Pure functions; the parser and the layer generator both call them, so what a test
// checks is what a run uses.
#include <cstdint>
#include <vector>

#include "solver/dem/dem_config.hpp"

namespace dustlift {

/// Phi^-1(p), the standard normal quantile, for 0 < p < 1 (Newton on Phi = erfc / 2; good to
/// a few ulp).
double standard_normal_quantile(double p);

/// A log-normal MASS distribution (Hinds, Aerosol Technology, 2nd ed., 1999, ch. 4: ln d is
/// normal with mean ln(mass median diameter) and standard deviation ln sigma_g) cut into
/// `classes` classes of equal mass fraction 1/N; class k (from 0, smallest first) has the
/// diameter of the distribution's mass quantile at (k + 1/2) / N:
///   d_k = median exp(ln(sigma_g) Phi^-1((k + 1/2) / N)).
/// Throws std::invalid_argument unless median > 0, sigma_g > 1 and classes >= 1.
std::vector<SizeClass> lognormal_classes(double median, double geometric_std, int classes);

/// The mass median diameter of discrete classes (ascending): the diameter of the first class
/// at which the cumulative mass fraction reaches 1/2.
double mass_median_diameter(const std::vector<SizeClass>& classes);

/// Whole counts summing to `total` closest to total * fraction_k (fractions summing to 1):
/// each class gets the floor, and the units left go to the largest remainders (ties: the
/// smaller class index). The Hamilton (largest remainder) apportionment.
std::vector<std::int64_t> largest_remainder_counts(std::int64_t total,
                                                   const std::vector<double>& fractions);

/// The class of each of sum(counts) sites: counts[k] sites of class k, in an order shuffled
/// by `seed` (Fisher-Yates over std::mt19937_64 with a rejection-sampled bounded integer:
/// the same on every standard library, unlike std::shuffle and the distributions).
std::vector<int> shuffled_classes(const std::vector<std::int64_t>& counts, std::uint64_t seed);

/// The size classes of a layer file's parcels (arrangement = file): the distinct particle
/// diameters (a parcel without one has `reference_d`, particles.diameter), ascending, each
/// with its share of the layer's solid, a parcel of diameter D holding (D / parcel_d)^2 times
/// the solid of one of parcel_d. Empty when no parcel gives a particle diameter.
std::vector<SizeClass> file_size_classes(const std::vector<PlacedParcel>& parcels,
                                         double reference_d, double parcel_d);

/// The class of a real particle diameter among `classes` (its index; -1 if none matches).
int size_class_of(const std::vector<SizeClass>& classes, double diameter);

/// Real particles per metre in a parcel of class diameter d that holds the solid volume of
/// a parcel of n_ref particles of diameter d_ref: n_ref (d_ref / d)^3 (n_ref itself when
/// d == d_ref, so a one-class layer keeps its bits).
double same_volume_real_per_parcel(double n_ref, double d_ref, double d);

}  // namespace dustlift
