#include "solver/app/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

#include "insitu/lifting_delay.hpp"
#include "insitu/series_table.hpp"
#include "insitu/surface_height.hpp"

namespace dustlift {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::optional<SeriesTable> read_if_present(const std::string& h5, const std::string& name) {
  try {
    return read_series_h5(h5, name);
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
}

/// Index of the column called `name`, or -1.
int column_of(const SeriesTable& t, const std::string& name) {
  for (std::size_t k = 0; k < t.columns().size(); ++k)
    if (t.columns()[k].name == name) return static_cast<int>(k);
  return -1;
}

ForcePeak signed_extreme(const SeriesTable& t, int tau_column, int value_column) {
  ForcePeak peak{kNaN, kNaN};
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double v = t.column(static_cast<std::size_t>(value_column))[r];
    if (std::isfinite(v) && !(std::abs(v) <= std::abs(peak.value))) {
      peak.value = v;
      peak.tau = t.column(static_cast<std::size_t>(tau_column))[r];
    }
  }
  return peak;
}

}  // namespace

RunResults summarise_run(const std::string& folder, const Scene& scene,
                         const std::vector<double>& stations, double lift_threshold) {
  const std::string h5 = (std::filesystem::path(folder) / "series" / "series.h5").string();
  RunResults r;
  r.profile_time = r.shock_x = r.lifting_delay = r.layer_top = kNaN;
  r.heights.assign(stations.size(), kNaN);

  // The surface profile of the last output, and the undisturbed top: the median height of
  // the first output (t = 0), which is the layer's top to 0.1 cell whatever the arrangement
  // (a settled bed's lies below the rectangle's y_max), except for a looser top (below).
  std::vector<double> xs, hs, first;
  double layer_top = scene.particles.layer.y_max;
  if (const auto surface = read_if_present(h5, "surface_height"); surface && surface->rows() > 0) {
    const auto& time = surface->column(0);
    r.profile_time = time.back();
    for (std::size_t k = 0; k < surface->rows(); ++k) {
      if (time[k] == time.front()) first.push_back(surface->column(2)[k]);
      if (time[k] != r.profile_time) continue;
      xs.push_back(surface->column(1)[k]);
      hs.push_back(surface->column(2)[k]);
    }
    // A looser top reads as a partly filled top cell at t = 0 (below y_max), which the first
    // shuffle of its loose parcels fills: lifting counts from the columns' top instead
    // (docs/dem.md, "A looser top"; analysis/paper_compare.py does the same).
    if (scene.particles.layer.loose_top_rows == 0) {
      std::nth_element(first.begin(), first.begin() + static_cast<std::ptrdiff_t>(first.size() / 2),
                       first.end());
      layer_top = first[first.size() / 2];
    }
    r.layer_top = layer_top;
    for (std::size_t s = 0; s < stations.size(); ++s)
      r.heights[s] = height_at_station(xs, hs, stations[s]);
  }
  // The shock when the surface profile was taken (the last sample at or before it).
  if (const auto shock = read_if_present(h5, "shock_position"); shock && shock->rows() > 0) {
    for (std::size_t k = 0; k < shock->rows(); ++k)
      if (!(shock->column(0)[k] > r.profile_time)) r.shock_x = shock->column(1)[k];
  }
  if (!xs.empty() && std::isfinite(r.shock_x)) {
    r.lifting_delay = lifting_delay_distance(xs, hs, r.shock_x, layer_top,
                                             scene.particles.layer.x_max, lift_threshold);
  }
  r.cloud.assign(kSummaryCloudColumns.size(), kNaN);
  if (const auto cloud = read_if_present(h5, "dust_cloud"); cloud && cloud->rows() > 0) {
    for (std::size_t c = 0; c < kSummaryCloudColumns.size(); ++c) {
      const int k = column_of(*cloud, kSummaryCloudColumns[c].series);
      if (k >= 0) r.cloud[c] = cloud->column(static_cast<std::size_t>(k)).back();
    }
  }
  for (const BandConfig& band : scene.output.bands) {
    std::vector<ForcePeak> peaks(kSummaryForceColumns.size(), ForcePeak{kNaN, kNaN});
    if (const auto t = read_if_present(h5, "forces_" + band.name)) {
      for (std::size_t c = 0; c < kSummaryForceColumns.size(); ++c) {
        const int k = column_of(*t, kSummaryForceColumns[c]);
        if (k >= 0) peaks[c] = signed_extreme(*t, 0, k);
      }
    }
    r.peaks.push_back(std::move(peaks));
  }
  return r;
}

}  // namespace dustlift
