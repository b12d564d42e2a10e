#pragma once
// Band-averaged force histories aligned to shock arrival (paper Figs. 10 and 12).
// Parcels are selected by their INITIAL position (a band of the layer); each sample is
// binned by tau = t - t_arrival, the time since the shock reached that parcel, and the
// bins hold plain means over every (parcel, sample time) that fell in them. The contact
// force is spiky (collisions last microseconds), so it is also averaged over coarser
// windows (0.01 ms by default). Serial, fixed-order sums: reproducible bit for bit.
#include <array>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "insitu/parcel_arrays.hpp"
#include "insitu/series_table.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

/// Parcel arrays the band filter reads, each `count` long. Absent force parts or Magnus
/// inputs (empty spans) give NaN columns.
struct BandParcelsView {
  std::size_t count = 0;
  Vec2Columns initial_position;                                         ///< m
  std::span<const double> y;                                            ///< m, current height
  Vec2Columns force_contact, force_drag, force_magnus, force_pressure;  ///< N
  std::span<const double> arrival_time;       ///< s; NaN: shock not arrived yet (skipped)
  std::span<const double> relative_rotation;  ///< rad/s, Magnus input w_r (DEM convention)
  std::span<const double> particle_rotation;  ///< rad/s, w_p
  std::span<const double> gas_rotation;       ///< rad/s, gas rotation (half vorticity) at parcel
};

struct Band {
  std::string name;                                   ///< used in the series name forces_<name>
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;  ///< m, box of initial positions
  bool contains(double x0, double y0) const {
    return x0 >= x_min && x0 < x_max && y0 >= y_min && y0 < y_max;
  }
};

struct BandAverageOptions {
  double tau_min = 0.0;          ///< s, first bin start (negative: before arrival)
  double tau_max = 1e-3;         ///< s, last bin end
  double bin_width = 1e-6;       ///< s
  double contact_window = 1e-5;  ///< s, window of the extra contact-force average
};

/// When the shock reached each x: the sampled shock positions with their running maximum,
/// so that the arrival time of a parcel is a function of its initial x alone (no per-parcel
/// state to keep in the parcel order, which the DEM changes; and a short series a checkpoint
/// can carry). arrival_time(x0) is the first sample time at which the shock stood at or
/// beyond x0 (NaN if not yet), as a parcel-by-parcel check at every sample would find.
class ShockTrajectory {
 public:
  /// Adds a sample; NaN positions (no shock found) are ignored. Times must not decrease.
  /// A position more than `max_advance` (m) beyond the reach is ignored too and counted: a
  /// shock sampled every step moves less than a cell per step (CFL <= 1), so such a jump is a
  /// pressure pulse ahead of it, which would date every arrival beyond it early.
  void record(double time, double shock_x,
              double max_advance = std::numeric_limits<double>::infinity());
  /// Samples ignored as jumps beyond max_advance.
  std::size_t ignored_jumps() const { return ignored_jumps_; }
  double arrival_time(double x0) const;
  /// Farthest position reached (NaN before the first sample).
  double reach() const;
  /// Samples at which the reach grew: (time, reach) pairs in order.
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& reaches() const { return reaches_; }
  /// Restores the pairs (a checkpoint); throws std::invalid_argument if they are not ordered.
  void assign(std::vector<double> times, std::vector<double> reaches);

 private:
  std::vector<double> times_, reaches_;  ///< reaches_ strictly increasing
  std::size_t ignored_jumps_ = 0;
};

/// Fills arrival_time[k] = trajectory.arrival_time(initial_x[k]) for the parcels whose
/// initial position lies in one of the bands (NaN for the others: they are not averaged).
void band_arrival_times(const ShockTrajectory& trajectory, const std::vector<Band>& bands,
                        std::span<const double> initial_x, std::span<const double> initial_y,
                        std::span<double> arrival_time);

class BandForceAccumulator {
 public:
  /// Averaged quantities, in column order after tau and samples.
  enum Quantity : std::size_t {
    kHeight,
    kContactX,
    kContactY,
    kDragX,
    kDragY,
    kMagnusX,
    kMagnusY,
    kPressureX,
    kPressureY,
    kRelativeRotation,
    kParticleRotation,
    kGasRotation,
    kQuantityCount
  };

  BandForceAccumulator(Band band, BandAverageOptions options = {});

  /// Adds every parcel of the band that the shock has reached, at simulated time `time`.
  void add(const BandParcelsView& parcels, double time);

  std::size_t bins() const { return count_.size(); }
  double bin_center(std::size_t bin) const;
  /// Number of (parcel, time) samples in a bin.
  std::size_t samples(std::size_t bin) const { return count_[bin]; }
  /// Mean of quantity q in a bin (NaN when the bin has no sample of it).
  double mean(Quantity q, std::size_t bin) const;
  /// Contact force (component 0 = x, 1 = y) averaged over the window holding the bin centre.
  double contact_window_mean(int component, std::size_t bin) const;

  /// Series forces_<band>: tau_s, samples_1, height_m, contact_x_N, ..., pressure_y_N,
  /// contact_window_x_N, contact_window_y_N, relative_rotation_rad/s, particle_rotation_rad/s,
  /// gas_rotation_rad/s; one row per non-empty bin. A fresh table: SeriesSink rewrites it.
  SeriesTable table() const;
  const Band& band() const { return band_; }

  /// Checkpoint state (the sums and counts of every bin and window) under `prefix`.
  void save_state(Snapshot& s, const std::string& prefix) const;
  /// Takes it back. The bins are aligned to tau_min and fixed widths, so a state with fewer
  /// bins (a run extended to a later end time, whose default duration grew) fills the first
  /// ones; one with more drops the bins beyond tau_max. SnapshotError when it does not fit.
  void restore_state(const Snapshot& s, const std::string& prefix);

 private:
  Band band_;
  BandAverageOptions options_;
  std::vector<std::size_t> count_;
  std::array<std::vector<double>, kQuantityCount> sum_;
  std::array<std::vector<std::size_t>, kQuantityCount> quantity_count_;
  std::array<std::vector<double>, 2> window_sum_;
  std::vector<std::size_t> window_count_;
};

/// The bands of one run and their CSV/HDF5 output (series/forces_<band>.csv): the lead's
/// ParcelSystem observer builds a BandParcelsView and calls add() then write().
class BandForceSeries {
 public:
  BandForceSeries(const std::vector<Band>& bands, BandAverageOptions options = {});
  void add(const BandParcelsView& parcels, double time);
  void write(const SeriesSink& sink) const;
  const std::vector<BandForceAccumulator>& accumulators() const { return accumulators_; }
  /// Every band's state, under <prefix><band name>/.
  void save_state(Snapshot& s, const std::string& prefix) const;
  void restore_state(const Snapshot& s, const std::string& prefix);

 private:
  std::vector<BandForceAccumulator> accumulators_;
};

}  // namespace dustlift
