#include "insitu/entrainment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "insitu/series_state.hpp"

namespace dustlift {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

Entrainment::Entrainment(EntrainmentOptions options)
    : o_(std::move(options)),
      bins_(o_.x_origin, o_.bin_width, o_.x_start, o_.x_end),
      above_(o_.heights.size() + 1) {}

double Entrainment::level(std::size_t k) const {
  return o_.layer_top + (k == 0 ? o_.lift_height : o_.heights[k - 1]);
}

EntrainmentSample Entrainment::sample(const EntrainmentParcels& p, double time) {
  const std::size_t n = p.id.size();
  if (p.x.size() != n || p.y.size() != n || p.x_initial.size() != n || p.mass.size() != n)
    throw std::invalid_argument("entrainment: the parcel columns differ in length");
  std::int32_t ids = 0;
  for (std::int32_t id : p.id) {
    if (id < 0) throw std::invalid_argument("entrainment: a parcel id is negative");
    ids = std::max(ids, id + 1);
  }
  const std::size_t levels = above_.size(), nb = bins_.count;
  EntrainmentSample s;
  s.has_rates = started_ && time > last_time_;
  s.interval = started_ ? time - last_time_ : 0.0;
  s.height_rate.assign(o_.heights.size(), 0.0);
  s.bin_x.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) s.bin_x[b] = 0.5 * (bins_.lo(b) + bins_.hi(b));
  s.entrainment.assign(nb, 0.0);
  s.height_flux.assign(o_.heights.size(), std::vector<double>(nb, 0.0));

  // Net crossings of every level since the last sample: mass, binned.
  std::vector<std::vector<double>> heights_mass(nb), heights_now(nb);
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = static_cast<std::size_t>(p.id[i]);
    const std::size_t now_bin = bins_.bin_of(p.x[i]);
    for (std::size_t k = 0; k < levels; ++k) {
      std::vector<std::int8_t>& side = above_[k];
      if (side.size() < static_cast<std::size_t>(ids))
        side.resize(static_cast<std::size_t>(ids), 0);
      const std::int8_t now = p.y[i] > level(k) ? 1 : 0;
      const int crossed = now - side[id];
      side[id] = now;
      if (crossed == 0 || !started_) continue;
      const double m = crossed * p.mass[i];
      if (k == 0) {
        s.lifted_rate += m;
        s.entrainment[bins_.bin_of(p.x_initial[i])] += m;
      } else {
        s.height_rate[k - 1] += m;
        s.height_flux[k - 1][now_bin] += m;
      }
    }
    if (above_[0][id] != 0) {  // lifted now: the cloud's height over its bin
      heights_mass[now_bin].push_back(p.mass[i]);
      heights_now[now_bin].push_back(p.y[i] - o_.layer_top);
    }
  }
  // Rates: per second, and per metre of channel for the binned ones.
  const double per_second = s.has_rates ? 1.0 / s.interval : kNaN;
  s.lifted_rate *= per_second;
  for (double& r : s.height_rate) r *= per_second;
  for (std::size_t b = 0; b < nb; ++b) {
    const double per_length = per_second / bins_.length(b);
    s.entrainment[b] *= per_length;
    for (auto& flux : s.height_flux) flux[b] *= per_length;
  }
  s.height_p90.assign(nb, kNaN);
  s.height_max.assign(nb, kNaN);
  for (std::size_t b = 0; b < nb; ++b) {
    if (heights_now[b].empty()) continue;
    s.height_p90[b] = weighted_quantile(heights_now[b], heights_mass[b], 0.9, order_);
    s.height_max[b] = *std::max_element(heights_now[b].begin(), heights_now[b].end());
  }
  started_ = true;
  last_time_ = time;
  return s;
}

void Entrainment::save(Snapshot& s, const std::string& prefix) const {
  for (std::size_t k = 0; k < above_.size(); ++k)
    s.i8[fmt::format("{}above_level{}", prefix, k)] = above_[k];
  save_time(last_time_, started_, s, prefix + "entrainment_last_time");
}

void Entrainment::restore(const Snapshot& s, const std::string& prefix) {
  for (std::size_t k = 0; k < above_.size(); ++k)
    above_[k] = snapshot_array(s.i8, fmt::format("{}above_level{}", prefix, k));
  started_ = restore_time(last_time_, s, prefix + "entrainment_last_time");
}

}  // namespace dustlift
