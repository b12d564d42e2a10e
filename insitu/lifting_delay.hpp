#pragma once
// Lifting delay distance (paper section 3.2): how far behind the shock the dust surface
// starts to rise. Pure function on a surface profile h(x) at one time.
#include <span>

namespace dustlift {

/// Default rise (m) above the undisturbed layer top that counts as lifting: one cell of the
/// paper's grid (0.25 mm), 2.5 particle diameters. It is 10x the sub-cell surface height's
/// error at t = 0 (0.1 cell) and above the 0.06-0.26 mm the shock first presses the
/// surface down, so neither reads as lifting; the paper's lifting heights are 1-30 mm.
inline constexpr double kDefaultLiftThreshold = 0.25e-3;

/// Scanning from the shock towards -x over the columns (x increasing, heights NaN where a
/// column has no particles), finds the first place where h rises above layer_top +
/// lift_threshold (linear interpolation between the two columns around the crossing) and
/// returns shock_x minus that x. Columns ahead of the shock are ignored. NaN when the
/// surface nowhere behind the shock rises that high, when shock_x is not finite, or when
/// the shock has left the layer (shock_x > layer_x_max, the layer's downstream end): the
/// delay is a distance behind a shock that still runs over dust.
double lifting_delay_distance(std::span<const double> x_centers, std::span<const double> heights,
                              double shock_x, double layer_top, double layer_x_max,
                              double lift_threshold = kDefaultLiftThreshold);

}  // namespace dustlift
