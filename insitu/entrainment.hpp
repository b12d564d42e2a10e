#pragma once
// How fast the shock entrains the layer, and where: the rate at which mass leaves the layer
// per unit length of layer against the distance behind the shock, the vertical dust mass flux
// through given heights, and the cloud's height over each stretch of channel. VTK-free; the
// dust-cloud observer (series dust_entrainment and the rate columns of dust_cloud) calls it
// at outputs.
//
// "Leaves the layer": a parcel's centre rises above layer_top + lift_height, the height above
// which the dust cloud counts it as lifted (dust_cloud.hpp). Between two samples the net
// mass that crossed a level upwards (parcels that fell back below it count negative) over
// the interval is the rate, so the rates summed over the samples times their intervals are
// the lifted mass's change: the entrainment rate integrated over time is the lifted mass.
// Each parcel's side of every level at the last sample is kept by parcel id (and in
// checkpoints).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "insitu/dust_cloud.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

struct EntrainmentOptions {
  double layer_top = 0.0;       ///< m, the initial layer's top
  double lift_height = 0.0;     ///< m, lifted above layer_top + this (dust_cloud.hpp)
  std::vector<double> heights;  ///< m above layer_top: the levels of the vertical fluxes
  /// Stretches of channel: bins of this width (m) aligned with x_origin over [x_start, x_end]
  double bin_width = 0.0, x_origin = 0.0, x_start = 0.0, x_end = 0.0;
};

/// The parcels as the entrainment reads them (one entry per parcel, any order).
struct EntrainmentParcels {
  std::span<const std::int32_t> id;   ///< 0 .. (parcels ever made) - 1
  std::span<const double> x, y;       ///< m, centres
  std::span<const double> x_initial;  ///< m, where the parcel started
  std::span<const double> mass;       ///< kg/m
};

/// The rates since the previous sample.
struct EntrainmentSample {
  bool has_rates = false;  ///< false at the first sample (nothing to difference yet)
  double interval = 0.0;   ///< s since the previous sample
  /// kg/(m s) (per metre of span): net mass that rose above the lift height per second
  double lifted_rate = 0.0;
  std::vector<double> height_rate;  ///< kg/(m s), the same through each of `heights`
  std::vector<double> bin_x;        ///< m, the bins' centres (clipped to the channel)
  /// kg/(m^2 s): the lifted rate per metre of layer, binned by where its parcels started
  std::vector<double> entrainment;
  /// kg/(m^2 s), [height][bin]: the net upward mass flux through each height, binned by where
  /// the parcels that crossed are now
  std::vector<std::vector<double>> height_flux;
  /// m above layer_top: the heights under which 90 % of the lifted mass now in the bin lies,
  /// and the highest lifted parcel's centre there (NaN where the bin holds none)
  std::vector<double> height_p90, height_max;
};

class Entrainment {
 public:
  explicit Entrainment(EntrainmentOptions options);
  /// The rates since the previous call (none at the first), and the parcels' sides of every
  /// level recorded for the next. Throws std::invalid_argument when the spans' sizes differ
  /// or an id is negative.
  EntrainmentSample sample(const EntrainmentParcels& parcels, double time);
  /// The parcels' sides of the levels and the last sample's time, under `prefix`.
  void save(Snapshot& s, const std::string& prefix) const;
  void restore(const Snapshot& s, const std::string& prefix);

 private:
  double level(std::size_t k) const;
  EntrainmentOptions o_;
  AlignedBins bins_;
  std::vector<std::vector<std::int8_t>> above_;  ///< [level][id]: 1 above, 0 not
  double last_time_ = 0.0;
  bool started_ = false;
  std::vector<std::size_t> order_;
};

}  // namespace dustlift
