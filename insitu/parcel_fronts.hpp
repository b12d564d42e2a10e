#pragma once
// The streamwise extent of a cloud of parcels (a particle curtain's upstream and downstream
// fronts): the smallest and largest x, and the x below which a share of the real particles
// lies. Experiments see a front as the edge of a schlieren or x-ray image, which lies
// between the outermost particle and the bulk; codes report the outermost particle (ppiclF)
// or the 1 % and 99 % points (jCODE). VTK-free.
#include <span>
#include <vector>

namespace dustlift {

struct ParcelFronts {
  double x_min = 0.0, x_max = 0.0;  ///< m, the outermost parcels
  double x_low = 0.0,
         x_high = 0.0;  ///< m, the x below which `share` / 1 - `share` of the particles lie
};

/// The fronts of parcels at x (m), each standing for `weight` real particles (> 0). `share`
/// in (0, 0.5): x_low is the smallest x with at least share W of the weight at or below it,
/// x_high the smallest x with at least (1 - share) W. `order` is scratch. Throws
/// std::invalid_argument for no parcels or mismatched sizes.
ParcelFronts parcel_fronts(std::span<const double> x, std::span<const double> weight, double share,
                           std::vector<std::size_t>& order);

/// A line of sight across the channel through a cloud of parcels (a schlieren or shadowgraph
/// image through a square tube): per streamwise bin of width `bin`, the optical depth
/// tau = n (pi d^2 / 4) depth of the real particles the bin holds (n their number per volume,
/// averaged over the channel `height`), and the edges where tau falls below `optical_depth`.
struct LineOfSight {
  double depth = 0.0, optical_depth = 1.0, bin = 0.0, height = 0.0;  ///< m, 1, m, m
};
struct SightEdges {
  /// m: the outermost x upstream and downstream where tau crosses the threshold (linear
  /// between bin centres); NaN where no bin reaches it.
  double upstream = 0.0, downstream = 0.0;
};
/// The optical depth per bin: bin k spans [(first + k) bin, (first + k + 1) bin) on a fixed
/// grid of x (multiples of the bin width), so runs and parcel orders share their bins.
struct SightProfile {
  double first = 0.0;        ///< index of the first bin (a whole number)
  std::vector<double> tau;   ///< optical depth per bin
};
/// The profile of parcels at x (m), each with `n_real` real particles per metre of depth of
/// diameter `diameter` (m). Throws std::invalid_argument for mismatched sizes or a
/// non-positive bin, height or depth.
void line_of_sight_profile(std::span<const double> x, std::span<const double> n_real,
                           std::span<const double> diameter, const LineOfSight& sight,
                           SightProfile& profile);
/// Where a profile crosses the threshold, outermost upstream and downstream.
SightEdges sight_edges(const SightProfile& profile, const LineOfSight& sight);
/// Both in one.
SightEdges line_of_sight_edges(std::span<const double> x, std::span<const double> n_real,
                               std::span<const double> diameter, const LineOfSight& sight,
                               SightProfile& profile);

}  // namespace dustlift
