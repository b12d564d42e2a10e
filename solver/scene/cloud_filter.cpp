#include "solver/scene/cloud_filter.hpp"

#include <algorithm>
#include <cmath>

#include "solver/dem/class_columns.hpp"
#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"

namespace dustlift {

double largest_parcel_mass(const DemConfig& dem) {
  const double particle = dem.density * sphere_volume(dem.particle_diameter);
  if (dem.layer.arrangement == LayerArrangement::File) {
    // A file's parcel of diameter D_i holds (D_i / D)^2 real_per_parcel particles of
    // particles.diameter, or the same solid volume of its own particles.
    double largest = 0.0;
    for (const PlacedParcel& p : dem.layer_parcels) {
      const double scale = p.diameter / dem.parcel_diameter;
      largest = std::max(largest, dem.real_per_parcel * scale * scale * particle);
    }
    return largest;
  }
  if (dem.real_per_parcel > 0.0) return dem.real_per_parcel * particle;
  if (has_class_parcels(dem.size_classes)) {
    // Parcels of a size per class: each class's parcel holds its own count.
    const ClassColumns plan = plan_class_columns(dem);
    double largest = 0.0;
    for (std::size_t k = 0; k < dem.size_classes.size(); ++k)
      largest = std::max(largest, plan.real_per_parcel[k] * dem.density *
                                      sphere_volume(dem.size_classes[k].diameter));
    return largest;
  }
  // Size classes: every parcel holds the same solid volume, alpha_p A / N.
  const LayerConfig& L = dem.layer;
  const double area = (L.x_max - L.x_min) * (L.y_max - L.y_min);
  const auto n = static_cast<double>(plan_layer(L, dem.parcel_diameter).n_parcels);
  return dem.density * L.volume_fraction * area / n;
}

double default_cloud_filter_width(double parcel_mass, double lower, double room) {
  const double width = std::sqrt(parcel_mass / (kFilterQuantumShare * lower));
  // A layer that fills the channel (a bed across a shock tube) leaves no room: nothing can be
  // lifted there, and the width need not fit.
  return room > 0.0 ? std::min(width, room) : width;
}

}  // namespace dustlift
