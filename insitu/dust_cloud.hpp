#pragma once
// The lifted dust cloud of a run, as a dust-explosion study reads it: how much dust mass is in
// the air, how high, at what concentration, how hot and how far behind the shock. A secondary
// explosion needs dust suspended above its minimum explosible concentration where the
// shock-heated gas or a flame reaches it (Eckhoff 2003, Dust Explosions in the Process
// Industries, ch. 1). VTK-free; the dust-cloud observer (series dust_cloud) calls it at outputs.
//
// Units: 2-D, per metre of depth. Masses are kg per metre of span; areas m^2 in the x-y plane.
#include <cstddef>
#include <span>
#include <vector>

namespace dustlift {

/// The parcels as the cloud reads them (one entry per parcel, any order).
struct CloudParcels {
  std::span<const double> x, y;         ///< m, centres
  std::span<const double> mass;         ///< kg/m, the parcel's (all its real particles)
  std::span<const double> temperature;  ///< K
  std::span<const double> size_class;   ///< 0 .. classes - 1 (empty: every parcel in class 0)
};

/// The dust concentration on the interior cells (x fastest, nx * ny values, kg/m^3) and the
/// cell faces.
struct CloudField {
  std::span<const double> x_faces;        ///< m, nx + 1
  std::span<const double> y_faces;        ///< m, ny + 1
  std::span<const double> concentration;  ///< kg/m^3
};

struct DustCloudOptions {
  double layer_top = 0.0;                  ///< m, the initial layer's top (heights count from it)
  double lift_height = 0.0;                ///< m, a parcel is lifted when y > layer_top + this
  double explosible_concentration = 0.05;  ///< kg/m^3
  double edge_concentration = 0.001;       ///< kg/m^3, the cloud top's level
  int classes = 1;                         ///< size classes of the layer
};

/// The lifted part of one size class (or of all of them).
struct LiftedDust {
  double lifted_mass = 0.0;   ///< kg/m
  double resting_mass = 0.0;  ///< kg/m, every parcel not lifted
  /// m above the layer top under which 50, 90, 99 % of the lifted mass lies (parcel centres;
  /// NaN when nothing is lifted)
  double height_p50 = 0.0, height_p90 = 0.0, height_p99 = 0.0;
  double temperature_max = 0.0;   ///< K, of the lifted parcels (NaN when none)
  double temperature_mean = 0.0;  ///< K, mass-weighted over the lifted parcels (NaN when none)
};

struct DustCloud {
  LiftedDust all;
  std::vector<LiftedDust> per_class;  ///< one per size class
  /// m above the layer top: the upper face of the highest cell row above it where the
  /// concentration reaches the edge level (0 when none does)
  double cloud_top = 0.0;
  /// m^2 of the cells above the layer top whose concentration reaches the explosible level,
  /// and their extent in x (NaN when none)
  double explosible_area = 0.0;
  double explosible_x_min = 0.0, explosible_x_max = 0.0;
  /// m, centre of the most downstream grid column holding lifted dust, and of the column
  /// holding the most lifted mass (NaN when nothing is lifted)
  double first_lifted_x = 0.0, densest_lifted_x = 0.0;
};

/// The cloud of `parcels` over `field`. `column_mass` is scratch. Throws
/// std::invalid_argument when the spans' sizes disagree or a size class is out of range.
DustCloud dust_cloud(const CloudParcels& parcels, const CloudField& field,
                     const DustCloudOptions& options, std::vector<double>& column_mass);

/// The smallest h such that the weights of the values at or below h reach `share` of their
/// total (values and weights paired; NaN when there are none). `order` is scratch.
double weighted_quantile(std::span<const double> values, std::span<const double> weights,
                         double share, std::vector<std::size_t>& order);

}  // namespace dustlift
