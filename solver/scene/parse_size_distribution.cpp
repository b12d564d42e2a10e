// [particles.size_distribution]: the size classes of a polydisperse layer (docs/dem.md,
// "Polydisperse layers"), as discrete classes or a log-normal mass distribution cut into
// classes of equal mass.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "solver/dem/size_distribution.hpp"
#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {
namespace {

/// Relative tolerance of the mass fractions' sum (a decimal list such as 0.1, 0.2, 0.7 sums
/// to 1 within a few ulp).
constexpr double kFractionSumTolerance = 1e-9;
/// More classes than this buy nothing (and each shrinks the parcels of its class count).
constexpr int kMaxClasses = 64;

std::string list_text(const std::vector<SizeClass>& classes, bool diameters) {
  std::string s = "[";
  for (std::size_t k = 0; k < classes.size(); ++k)
    s += fmt::format("{}{:.17g}", k ? ", " : "",
                     diameters ? classes[k].diameter : classes[k].mass_fraction);
  return s + "]";
}

}  // namespace

SizeDistribution parse_size_distribution(TableReader& sd) {
  sd.expect_keys({"diameters", "mass_fractions", "median", "geometric_std", "classes"});
  SizeDistribution out;
  const bool discrete = sd.has("diameters") || sd.has("mass_fractions");
  const bool lognormal = sd.has("median") || sd.has("geometric_std") || sd.has("classes");
  if (discrete && lognormal) {
    sd.fail(
        sd.has("median")          ? "median"
        : sd.has("geometric_std") ? "geometric_std"
                                  : "classes",
        "give either diameters and mass_fractions (discrete classes) or median and geometric_std "
        "(log-normal), not both");
  }
  if (!discrete && !lognormal) {
    sd.fail("diameters",
            "missing: give diameters and mass_fractions (discrete classes), or median and "
            "geometric_std (log-normal)");
  }
  if (discrete) {
    out.size_key = "diameters";
    out.count_key = "mass_fractions";
    if (!sd.has("diameters"))
      sd.fail("diameters", "missing (the classes' real particle diameters, m, ascending)");
    if (!sd.has("mass_fractions"))
      sd.fail("mass_fractions", "missing (each class's share of the layer's mass)");
    const std::vector<double> d = sd.number_list("diameters", {}, Range::positive());
    const std::vector<double> f = sd.number_list("mass_fractions", {}, Range::positive());
    if (d.empty()) sd.fail("diameters", "needs at least one class");
    if (static_cast<int>(d.size()) > kMaxClasses)
      sd.fail("diameters", fmt::format("at most {} classes", kMaxClasses));
    for (std::size_t k = 1; k < d.size(); ++k) {
      if (!(d[k] > d[k - 1])) {
        sd.fail("diameters", fmt::format("must be strictly ascending ({:.9g} m follows {:.9g} m)",
                                         d[k], d[k - 1]));
      }
    }
    if (f.size() != d.size()) {
      sd.fail("mass_fractions",
              fmt::format("has {} values but diameters has {}: one fraction per class", f.size(),
                          d.size()));
    }
    double sum = 0.0;
    for (double v : f) sum += v;
    if (!(std::fabs(sum - 1.0) <= kFractionSumTolerance)) {
      sd.fail("mass_fractions", fmt::format("sum to {:.17g}, not 1 (relative tolerance {:g})", sum,
                                            kFractionSumTolerance));
    }
    for (std::size_t k = 0; k < d.size(); ++k) out.classes.push_back({d[k], f[k]});
    out.mass_median = mass_median_diameter(out.classes);
  } else {
    out.size_key = "median";
    out.count_key = "classes";
    const double median = sd.required_number("median", Range::positive());
    const double sigma = sd.required_number("geometric_std", Range::positive());
    if (!(sigma > 1.0)) {
      sd.fail(
          "geometric_std",
          fmt::format("{:g} must be > 1 (1 is one size: set particles.diameter instead)", sigma));
    }
    const int n = static_cast<int>(sd.integer("classes", 5, 1, kMaxClasses));
    out.classes = lognormal_classes(median, sigma, n);
    out.mass_median = median;
    // The resolved scene shows the classes the cut made (comments: they derive again).
    sd.note_derived("diameters", list_text(out.classes, true),
                    "median, geometric_std and classes: the mass quantiles at (k + 1/2) / classes");
    sd.note_derived("mass_fractions", list_text(out.classes, false),
                    "classes (equal mass, 1 / classes)");
  }
  sd.finish();
  return out;
}

void check_class_sizes(const SizeDistribution& dist, const TableReader& sd, const DemConfig& dem,
                       const GridConfig& grid) {
  const double cell = min_cell_width(grid) * (1.0 + kCellTolerance);
  const double depth = dem.layer.y_max - dem.layer.y_min;
  for (const SizeClass& c : dist.classes) {
    if (c.diameter > cell) {
      sd.fail(dist.size_key,
              fmt::format("a class of {:.9g} m is larger than the smallest grid cell ({:.9g} m), "
                          "which breaks the unresolved-particle model (eqs. 12-16)",
                          c.diameter, cell));
    }
    if (c.diameter > depth) {
      sd.fail(dist.size_key,
              fmt::format("a class of {:.9g} m is larger than the layer's depth ({:.9g} m)",
                          c.diameter, depth));
    }
    if (c.diameter > dem.parcel_diameter) {
      sd.fail(
          dist.size_key,
          fmt::format("a class of {:.9g} m is larger than particles.parcel_diameter ({:.9g} m): "
                      "a parcel holds whole particles (n_xy >= 1, eq. 11)",
                      c.diameter, dem.parcel_diameter));
    }
  }
}

void check_class_counts(const SizeDistribution& dist, const TableReader& sd, std::int64_t placed) {
  std::vector<double> fractions;
  for (const SizeClass& c : dist.classes) fractions.push_back(c.mass_fraction);
  const std::vector<std::int64_t> counts = largest_remainder_counts(placed, fractions);
  for (std::size_t k = 0; k < counts.size(); ++k) {
    if (counts[k] == 0) {
      sd.fail(dist.count_key,
              fmt::format("the class of {:.9g} m gets no parcel of the layer's {} (its share "
                          "{:.3g} of them rounds to 0): fewer classes or smaller parcels",
                          dist.classes[k].diameter, placed, dist.classes[k].mass_fraction));
    }
  }
}

}  // namespace dustlift::scene_detail
