#include "insitu/band_average.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace dustlift {

void ShockTrajectory::record(double time, double shock_x, double max_advance) {
  if (std::isnan(shock_x)) return;
  if (!times_.empty() && time < times_.back())
    throw std::invalid_argument("ShockTrajectory: time went back");
  if (!reaches_.empty() && shock_x > reaches_.back() + max_advance) {
    ++ignored_jumps_;
    return;
  }
  if (reaches_.empty() || shock_x > reaches_.back()) {
    times_.push_back(time);
    reaches_.push_back(shock_x);
  }
}

double ShockTrajectory::arrival_time(double x0) const {
  // First recorded reach >= x0 (reaches_ is increasing).
  const auto it = std::lower_bound(reaches_.begin(), reaches_.end(), x0);
  if (it == reaches_.end()) return std::numeric_limits<double>::quiet_NaN();
  return times_[static_cast<std::size_t>(it - reaches_.begin())];
}

double ShockTrajectory::reach() const {
  return reaches_.empty() ? std::numeric_limits<double>::quiet_NaN() : reaches_.back();
}

void ShockTrajectory::assign(std::vector<double> times, std::vector<double> reaches) {
  if (times.size() != reaches.size()) throw std::invalid_argument("ShockTrajectory: sizes differ");
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] >= times[k - 1]) || !(reaches[k] > reaches[k - 1]))
      throw std::invalid_argument("ShockTrajectory: samples not in order");
  }
  times_ = std::move(times);
  reaches_ = std::move(reaches);
}

void band_arrival_times(const ShockTrajectory& trajectory, const std::vector<Band>& bands,
                        std::span<const double> initial_x, std::span<const double> initial_y,
                        std::span<double> arrival_time) {
  if (initial_x.size() != arrival_time.size() || initial_y.size() != arrival_time.size())
    throw std::invalid_argument("band_arrival_times: size mismatch");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Every step over every parcel, each on its own: in parallel.
  const auto n = static_cast<std::ptrdiff_t>(initial_x.size());
#pragma omp parallel for schedule(static) if (n >= 8192)
  for (std::ptrdiff_t q = 0; q < n; ++q) {
    const auto k = static_cast<std::size_t>(q);
    bool in_band = false;
    for (const Band& b : bands) in_band = in_band || b.contains(initial_x[k], initial_y[k]);
    arrival_time[k] = in_band ? trajectory.arrival_time(initial_x[k]) : nan;
  }
}

namespace {
std::size_t bin_count(double span, double width) {
  if (!(width > 0.0) || !(span > 0.0))
    throw std::invalid_argument("BandAverageOptions: need tau_max > tau_min and widths > 0");
  return static_cast<std::size_t>(std::ceil(span / width - 1e-9));
}

/// Bin of tau, or npos when outside [tau_min, tau_min + n * width).
constexpr std::size_t npos = static_cast<std::size_t>(-1);
std::size_t bin_of(double tau, double tau_min, double width, std::size_t n) {
  const double s = std::floor((tau - tau_min) / width);
  if (!(s >= 0.0) || s >= static_cast<double>(n)) return npos;
  return static_cast<std::size_t>(s);
}
}  // namespace

BandForceAccumulator::BandForceAccumulator(Band band, BandAverageOptions options)
    : band_(std::move(band)), options_(options) {
  const std::size_t n = bin_count(options_.tau_max - options_.tau_min, options_.bin_width);
  const std::size_t nw = bin_count(options_.tau_max - options_.tau_min, options_.contact_window);
  count_.assign(n, 0);
  for (auto& s : sum_) s.assign(n, 0.0);
  for (auto& c : quantity_count_) c.assign(n, 0);
  for (auto& s : window_sum_) s.assign(nw, 0.0);
  window_count_.assign(nw, 0);
}

void BandForceAccumulator::add(const BandParcelsView& p, double time) {
  if (p.initial_position.x.size() != p.count || p.initial_position.y.size() != p.count ||
      p.arrival_time.size() != p.count || p.y.size() != p.count)
    throw std::invalid_argument(
        "BandForceAccumulator: initial_position, y and arrival_time must hold count values");
  const std::size_t n = count_.size(), nw = window_count_.size();
  auto accumulate = [&](Quantity q, std::size_t bin, std::span<const double> values,
                        std::size_t k) {
    if (values.empty()) return;
    if (values.size() != p.count)
      throw std::invalid_argument("BandForceAccumulator: an array is not count long");
    sum_[q][bin] += values[k];
    ++quantity_count_[q][bin];
  };
  for (std::size_t k = 0; k < p.count; ++k) {
    if (!band_.contains(p.initial_position.x[k], p.initial_position.y[k])) continue;
    if (std::isnan(p.arrival_time[k])) continue;
    const double tau = time - p.arrival_time[k];
    const std::size_t bin = bin_of(tau, options_.tau_min, options_.bin_width, n);
    if (bin == npos) continue;
    ++count_[bin];
    accumulate(kHeight, bin, p.y, k);
    accumulate(kContactX, bin, p.force_contact.x, k);
    accumulate(kContactY, bin, p.force_contact.y, k);
    accumulate(kDragX, bin, p.force_drag.x, k);
    accumulate(kDragY, bin, p.force_drag.y, k);
    accumulate(kMagnusX, bin, p.force_magnus.x, k);
    accumulate(kMagnusY, bin, p.force_magnus.y, k);
    accumulate(kPressureX, bin, p.force_pressure.x, k);
    accumulate(kPressureY, bin, p.force_pressure.y, k);
    accumulate(kRelativeRotation, bin, p.relative_rotation, k);
    accumulate(kParticleRotation, bin, p.particle_rotation, k);
    accumulate(kGasRotation, bin, p.gas_rotation, k);
    if (p.force_contact.present()) {
      const std::size_t w = bin_of(tau, options_.tau_min, options_.contact_window, nw);
      if (w != npos) {
        window_sum_[0][w] += p.force_contact.x[k];
        window_sum_[1][w] += p.force_contact.y[k];
        ++window_count_[w];
      }
    }
  }
}

double BandForceAccumulator::bin_center(std::size_t bin) const {
  return options_.tau_min + (static_cast<double>(bin) + 0.5) * options_.bin_width;
}

double BandForceAccumulator::mean(Quantity q, std::size_t bin) const {
  const std::size_t c = quantity_count_[q][bin];
  return c ? sum_[q][bin] / static_cast<double>(c) : std::numeric_limits<double>::quiet_NaN();
}

double BandForceAccumulator::contact_window_mean(int component, std::size_t bin) const {
  const std::size_t w =
      bin_of(bin_center(bin), options_.tau_min, options_.contact_window, window_count_.size());
  if (w == npos || window_count_[w] == 0) return std::numeric_limits<double>::quiet_NaN();
  return window_sum_[static_cast<std::size_t>(component)][w] /
         static_cast<double>(window_count_[w]);
}

SeriesTable BandForceAccumulator::table() const {
  SeriesTable t("forces_" + band_.name, {{"tau", "s"},
                                         {"samples", "1"},
                                         {"height", "m"},
                                         {"contact_x", "N"},
                                         {"contact_y", "N"},
                                         {"drag_x", "N"},
                                         {"drag_y", "N"},
                                         {"magnus_x", "N"},
                                         {"magnus_y", "N"},
                                         {"pressure_x", "N"},
                                         {"pressure_y", "N"},
                                         {"contact_window_x", "N"},
                                         {"contact_window_y", "N"},
                                         {"relative_rotation", "rad/s"},
                                         {"particle_rotation", "rad/s"},
                                         {"gas_rotation", "rad/s"}});
  std::vector<double> row(t.columns().size());
  for (std::size_t b = 0; b < bins(); ++b) {
    if (count_[b] == 0) continue;
    std::size_t c = 0;
    row[c++] = bin_center(b);
    row[c++] = static_cast<double>(count_[b]);
    for (std::size_t q = kHeight; q <= kPressureY; ++q) row[c++] = mean(Quantity(q), b);
    row[c++] = contact_window_mean(0, b);
    row[c++] = contact_window_mean(1, b);
    for (std::size_t q = kRelativeRotation; q < kQuantityCount; ++q)
      row[c++] = mean(Quantity(q), b);
    t.append_row(row);
  }
  return t;
}

namespace {
std::vector<std::int64_t> as_int64(const std::vector<std::size_t>& v, std::size_t n) {
  return {v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n)};
}
std::vector<double> first(const std::vector<double>& v, std::size_t n) {
  return {v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n)};
}
/// Bins up to the last one with a sample: those after it are all zero (a long band duration
/// holds many bins no sample reached yet; the checkpoint stays small).
std::size_t used_bins(const std::vector<std::size_t>& count) {
  std::size_t n = count.size();
  while (n > 0 && count[n - 1] == 0) --n;
  return n;
}

/// Copies the stored bins into `into` (as many as both have); counts must not be negative.
template <class Stored, class Into>
void restore_bins(const std::vector<Stored>& stored, std::vector<Into>& into,
                  const std::string& name) {
  std::fill(into.begin(), into.end(), Into{});
  for (std::size_t b = 0; b < std::min(stored.size(), into.size()); ++b) {
    if constexpr (std::is_integral_v<Stored>) {
      if (stored[b] < 0) throw SnapshotError("array '" + name + "' holds a negative count");
    }
    into[b] = static_cast<Into>(stored[b]);
  }
}
}  // namespace

void BandForceAccumulator::save_state(Snapshot& s, const std::string& prefix) const {
  const std::size_t n = used_bins(count_), nw = used_bins(window_count_);
  s.i64[prefix + "samples"] = as_int64(count_, n);
  for (std::size_t q = 0; q < kQuantityCount; ++q) {
    s.f64[prefix + "sum_" + std::to_string(q)] = first(sum_[q], n);
    s.i64[prefix + "count_" + std::to_string(q)] = as_int64(quantity_count_[q], n);
  }
  s.f64[prefix + "window_sum_x"] = first(window_sum_[0], nw);
  s.f64[prefix + "window_sum_y"] = first(window_sum_[1], nw);
  s.i64[prefix + "window_samples"] = as_int64(window_count_, nw);
}

void BandForceAccumulator::restore_state(const Snapshot& s, const std::string& prefix) {
  const auto& samples = snapshot_array(s.i64, prefix + "samples");
  const std::size_t bins = samples.size();
  restore_bins(samples, count_, prefix + "samples");
  for (std::size_t q = 0; q < kQuantityCount; ++q) {
    const std::string sum = prefix + "sum_" + std::to_string(q),
                      count = prefix + "count_" + std::to_string(q);
    if (bins > 0) {
      restore_bins(snapshot_array(s.f64, sum, bins), sum_[q], sum);
      restore_bins(snapshot_array(s.i64, count, bins), quantity_count_[q], count);
    } else {
      std::fill(sum_[q].begin(), sum_[q].end(), 0.0);
      std::fill(quantity_count_[q].begin(), quantity_count_[q].end(), 0);
    }
  }
  const auto& windows = snapshot_array(s.i64, prefix + "window_samples");
  restore_bins(windows, window_count_, prefix + "window_samples");
  const std::size_t nw = windows.size();
  for (int c = 0; c < 2; ++c) {
    const std::string name = prefix + (c == 0 ? "window_sum_x" : "window_sum_y");
    if (nw > 0) {
      restore_bins(snapshot_array(s.f64, name, nw), window_sum_[c], name);
    } else {
      std::fill(window_sum_[c].begin(), window_sum_[c].end(), 0.0);
    }
  }
}

BandForceSeries::BandForceSeries(const std::vector<Band>& bands, BandAverageOptions options) {
  for (const auto& b : bands) accumulators_.emplace_back(b, options);
}

void BandForceSeries::add(const BandParcelsView& parcels, double time) {
  for (auto& a : accumulators_) a.add(parcels, time);
}

void BandForceSeries::write(const SeriesSink& sink) const {
  for (const auto& a : accumulators_) {
    SeriesTable t = a.table();
    sink.write(t);
  }
}

void BandForceSeries::save_state(Snapshot& s, const std::string& prefix) const {
  for (const auto& a : accumulators_) a.save_state(s, prefix + a.band().name + "/");
}

void BandForceSeries::restore_state(const Snapshot& s, const std::string& prefix) {
  for (auto& a : accumulators_) a.restore_state(s, prefix + a.band().name + "/");
}

}  // namespace dustlift
