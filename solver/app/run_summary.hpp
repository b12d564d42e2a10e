#pragma once
// Result quantities of one finished run, read back from its output folder (the series the
// observers wrote, docs/output.md): what a sweep's summary reports per run.
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"

namespace dustlift {

/// Signed extreme of one band-force component and the time since shock arrival it occurs at.
struct ForcePeak {
  double value = 0.0;  ///< N per parcel (the value of largest magnitude)
  double tau = 0.0;    ///< s
};

/// The band-force components a summary reports (vertical: the lifting direction).
/// Contact uses the 0.01 ms window average, as the paper plots it (section 3.4).
inline const std::vector<std::string> kSummaryForceColumns{"contact_window_y", "drag_y",
                                                           "pressure_y", "magnus_y"};

/// The dust-cloud quantities a summary reports at a run's end: the column of series
/// dust_cloud, its name in the summary and its unit.
struct SummaryCloudColumn {
  std::string series, summary, unit;
};
inline const std::vector<SummaryCloudColumn> kSummaryCloudColumns{
    {"lifted_mass", "cloud_lifted_mass", "kg/m"},
    {"lifted_share", "cloud_lifted_share", "1"},
    {"height_p90", "cloud_height_p90", "m"},
    {"cloud_top", "cloud_top", "m"},
    {"explosible_area", "cloud_explosible_area", "m^2"},
    {"explosible_mass", "cloud_explosible_mass", "kg/m"}};

struct RunResults {
  double profile_time = 0.0;  ///< s, time of the last surface-height output (NaN: none)
  double shock_x =
      0.0;  ///< m, shock position then, or at the end without particles (NaN: no shock series)
  double lifting_delay = 0.0;   ///< m, shock_x minus where the surface first rose (NaN: no lifting,
                                ///< or the shock beyond the layer's x_max)
  double layer_top = 0.0;       ///< m, the undisturbed top the rise is measured from
  std::vector<double> heights;  ///< m, h(x) at the end at each station (NaN where no particles)
  /// The dust cloud at the last output (series dust_cloud; NaN without it): the columns
  /// kSummaryCloudColumns name, in that order.
  std::vector<double> cloud;
  /// peaks[band][component], bands in scene order, components as kSummaryForceColumns;
  /// NaN where the band series is missing or empty.
  std::vector<std::vector<ForcePeak>> peaks;
};

/// Reads folder/series/series.h5. Stations in m; `lift_threshold` in m above the layer's
/// undisturbed top, the median surface height of the first output (t = 0; without a
/// surface series, scene.particles.layer.y_max). Missing series give NaN entries, not errors.
RunResults summarise_run(const std::string& folder, const Scene& scene,
                         const std::vector<double>& stations, double lift_threshold);

}  // namespace dustlift
