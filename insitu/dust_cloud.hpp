#pragma once
// The lifted dust cloud of a run, as a dust-explosion study reads it: how much dust mass is in
// the air, how high, at what concentration, how hot and how far behind the shock. A secondary
// explosion needs dust suspended inside its explosible range, between the minimum explosible
// concentration and an upper limit, where the shock-heated gas or a flame reaches it (Eckhoff
// 2003, Dust Explosions in the Process Industries, ch. 1). VTK-free; the dust-cloud observer
// (series dust_cloud, dust_concentration_histogram) calls it at outputs.
//
// The concentration that decides what is explosible is filtered: a moving average of the
// lifted parcels' mass over a square box of side `filter_width` that slides in steps of
// width / kFilterSubcells across the channel (docs/dust-cloud.md). One parcel alone in a box
// makes the concentration's quantum m_parcel / width^2, the step by which the filtered
// concentration changes; a width at which it is well below the lower limit lets the band's
// edges be resolved.
//
// Units: 2-D, per metre of depth. Masses are kg per metre of span; areas m^2 in the x-y plane.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "solver/scene/cloud_filter.hpp"

namespace dustlift {

/// The parcels as the cloud reads them (one entry per parcel, any order).
struct CloudParcels {
  std::span<const double> x, y;         ///< m, centres
  std::span<const double> mass;         ///< kg/m, the parcel's (all its real particles)
  std::span<const double> temperature;  ///< K
  std::span<const double> size_class;   ///< 0 .. classes - 1 (empty: every parcel in class 0)
  /// m, the real particles' diameter (empty: no parcel counts as fines)
  std::span<const double> particle_diameter = {};
};

/// The dust concentration on the flow grid's interior cells (x fastest, nx * ny values,
/// kg/m^3) and the cell faces: what the cloud's top is read from.
struct CloudField {
  std::span<const double> x_faces;        ///< m, nx + 1
  std::span<const double> y_faces;        ///< m, ny + 1
  std::span<const double> concentration;  ///< kg/m^3
};

/// The filter box's side in steps of its analysis lattice. The box slides in steps of
/// w / kFilterSubcells, so one parcel's share of the band changes in steps of 1/81 as it or
/// its neighbours move, and the band's edges are placed to w/9 (2.2 mm for 20 mm boxes), a
/// few per cent of a cloud some filter widths long; odd, so that each box is centred on a
/// sub-cell (no half-step shift of the field). The lattice holds k^2 sub-cells per w^2, kept
/// over the lifted dust's extent (plus a box) only, and the box sums cost 2k additions per
/// sub-cell and summed field: at most about 10^5 per output for the shipped scenes.
inline constexpr int kFilterSubcells = 9;

struct DustCloudOptions {
  double layer_top = 0.0;            ///< m, the initial layer's top (heights count from it)
  double lift_height = 0.0;          ///< m, a parcel is lifted when y > layer_top + this
  double top_concentration = 0.001;  ///< kg/m^3, the cloud top's level (flow grid)
  int classes = 1;                   ///< size classes of the layer
  /// The filtered concentration: square boxes of this side (m) sliding over a lattice of
  /// sub-cells of side filter_width / filter_subcells, aligned with `x_origin` and the layer
  /// top, over the channel x in [x_start, x_end], y in [layer_top, y_end].
  double filter_width = 0.0;
  int filter_subcells = kFilterSubcells;  ///< the box's side in sub-cells (tests use fewer)
  double x_origin = 0.0;                  ///< m, a sub-cell edge (the layer's upstream end)
  double x_start = 0.0, x_end = 0.0;      ///< m, the channel along x
  double y_end = 0.0;                     ///< m, the channel's top
  double explosible_lower = 0.05;         ///< kg/m^3, the band's lower edge (inclusive)
  double explosible_upper = 2.0;          ///< kg/m^3, the band's upper edge (inclusive)
  double fines_diameter = 75e-6;          ///< m, particles smaller than this are fines
  std::vector<double> heights;            ///< m above layer_top: mass above each is reported
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

/// Bins of one width along an axis, edges at origin + k width, clipped to [lo, hi] (the
/// entrainment's stretches of channel). A value outside falls in the nearest end bin.
struct AlignedBins {
  double origin, width, lo_edge, hi_edge;
  std::ptrdiff_t first = 0;  ///< index of the first bin counted from origin
  std::size_t count = 0;
  /// Throws std::invalid_argument unless width > 0 and hi > lo.
  AlignedBins(double origin, double width, double lo, double hi);
  double lo(std::size_t i) const;  ///< m, bin i's lower edge (clipped)
  double hi(std::size_t i) const;  ///< m, bin i's upper edge (clipped)
  double length(std::size_t i) const { return hi(i) - lo(i); }
  std::size_t bin_of(double v) const;
};

/// The concentration histogram's bins: log-spaced, kHistogramPerDecade per decade from
/// kHistogramLow to kHistogramHigh kg/m^3; a cell below the first bin counts in it, one
/// above the last in the last.
inline constexpr double kHistogramLow = 1e-4, kHistogramHigh = 1e4;
inline constexpr int kHistogramPerDecade = 10;
inline constexpr int kHistogramBins = 8 * kHistogramPerDecade;
/// Edge k (0 .. kHistogramBins) of the histogram, kg/m^3.
double histogram_edge(int k);

/// The filtered concentration and what the band makes of it. Each box position inside the
/// channel reads c = (lifted mass in the box) / (its area, w^2 away from the channel's far
/// ends). The lifted mass of each sub-cell is shared equally among the n box positions that
/// hold it (k^2 away from the channel's edges, fewer near them), and a box's share mu counts at
/// its concentration: its area is mu / c. Away from the edges this is the moving average
/// sampled at every sub-cell, the share c times the sub-cell's area; everywhere the shares add
/// up to the lifted mass.
struct FilteredCloud {
  double quantum = 0.0;  ///< kg/m^3, the largest parcel's mass / filter_width^2
  /// Boxes that hold lifted dust: the area of their shares (m^2) and the lifted mass over it
  /// (kg/m^3)
  double cloud_area = 0.0, cloud_concentration = 0.0;
  /// The boxes whose filtered concentration lies in [lower, upper]: their shares of the
  /// lifted mass (kg/m) and of the area (m^2), the mean concentration (mass / area; NaN when
  /// none) and the x-extent of the boxes (NaN when none)
  double explosible_mass = 0.0, explosible_area = 0.0, explosible_concentration = 0.0;
  double explosible_x_min = 0.0, explosible_x_max = 0.0;
  /// The fines (particle diameter below fines_diameter): their shares in the band's boxes and
  /// their mean concentration there (NaN when no box is in the band), and in all the lifted
  /// dust and over the cloud's area (NaN when nothing is lifted)
  double fines_explosible_mass = 0.0, fines_explosible_concentration = 0.0;
  double fines_lifted_mass = 0.0, fines_cloud_concentration = 0.0;
  /// Per histogram bin: the shares of the lifted mass, of the fines' mass (kg/m) and of the
  /// area (m^2) of the boxes whose concentration falls in it
  std::array<double, kHistogramBins> histogram_mass{}, histogram_fines{}, histogram_area{};
};

struct DustCloud {
  LiftedDust all;
  std::vector<LiftedDust> per_class;  ///< one per size class
  /// m above the layer top: the upper face of the highest flow-grid cell row above it where
  /// the concentration reaches top_concentration (0 when none does)
  double cloud_top = 0.0;
  FilteredCloud filtered;
  std::vector<double> mass_above;  ///< kg/m, above layer_top + heights[k]
  /// m, centre of the most downstream grid column holding lifted dust, and of the column
  /// holding the most lifted mass (NaN when nothing is lifted)
  double first_lifted_x = 0.0, densest_lifted_x = 0.0;
};

/// Scratch the cloud reuses between outputs.
struct DustCloudScratch {
  std::vector<double> column_mass;
  /// The lifted parcels' sub-cells of the filter's lattice (x, y), mass and fines' mass
  std::vector<std::size_t> lifted_ix, lifted_iy;
  std::vector<double> lifted_mass, lifted_fines;
  /// The filter's sub-cells and box positions over the lifted dust's extent
  std::vector<double> cell_mass, cell_fines, shares, fine_shares, rows, box_mass, box_share,
      box_fines;
};

/// The cloud of `parcels` over `field`. Throws std::invalid_argument when the spans' sizes
/// disagree, a size class is out of range, or the filter has no box.
DustCloud dust_cloud(const CloudParcels& parcels, const CloudField& field,
                     const DustCloudOptions& options, DustCloudScratch& scratch);

/// The filtered concentration's quantum: one parcel of `parcel_mass` (kg/m) alone in a box
/// of side `width` (m), kg/m^3.
inline double concentration_quantum(double parcel_mass, double width) {
  return parcel_mass / (width * width);
}

/// Whether a quantum is well below the lower limit: at most the share the default filter
/// width makes (kFilterQuantumShare, a tenth).
inline bool quantum_resolves(double quantum, double lower) {
  return quantum <= kFilterQuantumShare * lower * (1.0 + 1e-9);
}

/// A warning for the run's log and `dustlift info` when `quantum` (kg/m^3) is not well below
/// the band's lower limit, saying what width would resolve it and whether the channel
/// allows it; empty when it is.
std::string quantum_warning(double quantum, const DustCloudOptions& options);

/// The smallest h such that the weights of the values at or below h reach `share` of their
/// total (values and weights paired; NaN when there are none). `order` is scratch.
double weighted_quantile(std::span<const double> values, std::span<const double> weights,
                         double share, std::vector<std::size_t>& order);

}  // namespace dustlift
