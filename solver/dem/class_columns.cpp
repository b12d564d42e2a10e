// Columns of one size class each, for parcels of a size per class (class_columns.hpp).
#include "solver/dem/class_columns.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/size_distribution.hpp"

namespace dustlift {
namespace {

/// The centres of one column of parcels of diameter D, from the layer top down: each at least
/// D below the one above (no overlap by round-off), the lowest at least D/2 above the floor.
std::vector<double> column_centres(const LayerConfig& L, double D) {
  std::vector<double> y;
  const double r = 0.5 * D;
  double next = L.y_max - r;
  while (next - L.y_min >= r) {
    y.push_back(next);
    double below = next - D;
    while (next - below < D)
      below = std::nextafter(below, -std::numeric_limits<double>::infinity());
    next = below;
  }
  return y;
}

}  // namespace

ClassColumns plan_class_columns(const DemConfig& cfg) {
  const LayerConfig& L = cfg.layer;
  const double width = L.x_max - L.x_min, depth = L.y_max - L.y_min;
  const double alpha = L.volume_fraction;
  const std::size_t classes = cfg.size_classes.size();
  ClassColumns plan;
  std::vector<double> exact_width(classes);
  double filled = 0.0;
  for (std::size_t k = 0; k < classes; ++k) {
    const SizeClass& c = cfg.size_classes[k];
    const double D = c.parcel_diameter;
    const auto rows = static_cast<int>(column_centres(L, D).size());
    if (rows < 1)
      throw ClassColumnsError("parcels of " + std::to_string(D) + " m are deeper than the layer",
                              false);
    // Spread: as wide as holds alpha_p in the discs; touching: one parcel wide.
    exact_width[k] = L.touching_columns ? D : rows * disc_area(D) / (alpha * depth);
    const std::int64_t columns = std::llround(c.mass_fraction * width / exact_width[k]);
    if (columns < 1) {
      std::ostringstream s;
      s << "the class of " << c.diameter << " m gets no column of its " << D
        << " m parcels (its share " << c.mass_fraction << " of the layer's width is "
        << c.mass_fraction * width / exact_width[k] << " columns): a smaller parcel ratio or a "
        << "longer layer";
      throw ClassColumnsError(s.str(), false);
    }
    plan.rows.push_back(rows);
    plan.columns.push_back(columns);
    filled += static_cast<double>(columns) * exact_width[k];
  }
  // Touching columns may not be squeezed below their parcels' width: drop a column of the
  // class whose width share most exceeds its mass fraction until the columns fit.
  while (L.touching_columns && filled > width) {
    std::size_t worst = classes;
    double excess = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < classes; ++k) {
      const double over = static_cast<double>(plan.columns[k]) * exact_width[k] / width -
                          cfg.size_classes[k].mass_fraction;
      if (plan.columns[k] > 1 && over > excess) {
        excess = over;
        worst = k;
      }
    }
    if (worst == classes) throw ClassColumnsError("touching columns do not fit the layer", false);
    --plan.columns[worst];
    filled -= exact_width[worst];
  }
  plan.stretch = width / filled;
  for (std::size_t k = 0; k < classes; ++k) {
    const SizeClass& c = cfg.size_classes[k];
    const double w = exact_width[k] * plan.stretch;
    if (w < c.parcel_diameter) {
      std::ostringstream s;
      s << "volume fraction " << alpha << " needs columns of the " << c.diameter
        << " m class narrower (" << w << " m) than its parcels (" << c.parcel_diameter
        << " m): at most pi/4 rows D / depth in columns of touching parcels";
      throw ClassColumnsError(s.str(), true);
    }
    plan.width.push_back(w);
    plan.real_per_parcel.push_back(alpha * w * depth / (plan.rows[k] * sphere_volume(c.diameter)));
    plan.parcels += plan.columns[k] * plan.rows[k];
  }
  plan.order = shuffled_classes(plan.columns, L.seed);
  return plan;
}

ClassColumnParcels place_class_columns(const DemConfig& cfg, const ClassColumns& plan) {
  const LayerConfig& L = cfg.layer;
  std::vector<std::vector<double>> centres;
  for (const SizeClass& c : cfg.size_classes)
    centres.push_back(column_centres(L, c.parcel_diameter));
  ClassColumnParcels out;
  out.x.reserve(static_cast<std::size_t>(plan.parcels));
  out.y.reserve(static_cast<std::size_t>(plan.parcels));
  out.size_class.reserve(static_cast<std::size_t>(plan.parcels));
  double left = L.x_min, previous_x = 0.0, previous_radius = -1.0;
  for (int k : plan.order) {
    const auto kk = static_cast<std::size_t>(k);
    double x = left + 0.5 * plan.width[kk];
    // Touching columns: no pair of neighbouring columns overlaps by round-off.
    const double radius = 0.5 * cfg.size_classes[kk].parcel_diameter;
    if (previous_radius >= 0.0) {
      while (x - previous_x < previous_radius + radius)
        x = std::nextafter(x, std::numeric_limits<double>::infinity());
    }
    previous_x = x;
    previous_radius = radius;
    for (double y : centres[kk]) {
      out.x.push_back(x);
      out.y.push_back(y);
      out.size_class.push_back(k);
    }
    left += plan.width[kk];
  }
  return out;
}

std::string describe_class_columns(const DemConfig& cfg, const ClassColumns& plan) {
  const LayerConfig& L = cfg.layer;
  const double width = L.x_max - L.x_min;
  std::ostringstream s;
  s.precision(4);
  s << (L.touching_columns ? "touching " : "") << "columns of one class each (" << plan.order.size()
    << " columns, " << plan.parcels << " parcels, widths x " << plan.stretch
    << " of the exact fraction's):";
  for (std::size_t k = 0; k < cfg.size_classes.size(); ++k) {
    const SizeClass& c = cfg.size_classes[k];
    s << (k ? ";" : "") << " " << c.diameter * 1e6 << " um in " << c.parcel_diameter * 1e6
      << " um parcels (ratio " << c.parcel_diameter / c.diameter << "), " << plan.rows[k]
      << " rows x " << plan.columns[k] << " columns of " << plan.width[k] * 1e6
      << " um, mass fraction " << static_cast<double>(plan.columns[k]) * plan.width[k] / width;
  }
  return s.str();
}

}  // namespace dustlift
