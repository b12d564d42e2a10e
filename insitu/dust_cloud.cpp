#include "insitu/dust_cloud.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace dustlift {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Column of x among the faces (clamped to the grid: parcels at a wall sit in its cell).
std::size_t column_of(std::span<const double> faces, double x) {
  const auto it = std::upper_bound(faces.begin(), faces.end(), x);
  const std::ptrdiff_t i = (it - faces.begin()) - 1;
  return static_cast<std::size_t>(
      std::clamp<std::ptrdiff_t>(i, 0, static_cast<std::ptrdiff_t>(faces.size()) - 2));
}

/// Heights, mass and temperature of one class's lifted parcels, then its summary.
struct LiftedSample {
  std::vector<double> height, mass;
  double resting = 0.0, temperature_max = -std::numeric_limits<double>::infinity(), heat = 0.0;

  LiftedDust summary(std::vector<std::size_t>& order) const {
    LiftedDust d;
    d.resting_mass = resting;
    d.lifted_mass = std::accumulate(mass.begin(), mass.end(), 0.0);
    if (height.empty()) {
      d.height_p50 = d.height_p90 = d.height_p99 = d.temperature_max = d.temperature_mean = kNaN;
      return d;
    }
    d.height_p50 = weighted_quantile(height, mass, 0.50, order);
    d.height_p90 = weighted_quantile(height, mass, 0.90, order);
    d.height_p99 = weighted_quantile(height, mass, 0.99, order);
    d.temperature_max = temperature_max;
    d.temperature_mean = heat / d.lifted_mass;
    return d;
  }
};

}  // namespace

double weighted_quantile(std::span<const double> values, std::span<const double> weights,
                         double share, std::vector<std::size_t>& order) {
  if (values.size() != weights.size())
    throw std::invalid_argument("weighted_quantile: sizes differ");
  if (values.empty()) return kNaN;
  order.resize(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Ties broken by index: the same values give the same answer in any parcel order.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return values[a] < values[b] || (values[a] == values[b] && a < b);
  });
  double total = 0.0;
  for (std::size_t k : order) total += weights[k];
  const double target = share * total;
  double below = 0.0;
  for (std::size_t k : order) {
    below += weights[k];
    if (below >= target) return values[k];
  }
  return values[order.back()];
}

AlignedBins::AlignedBins(double origin_, double width_, double lo_, double hi_)
    : origin(origin_), width(width_), lo_edge(lo_), hi_edge(hi_) {
  if (!(width > 0.0) || !(hi_edge > lo_edge))
    throw std::invalid_argument("aligned bins: the width or the extent is not positive");
  first = static_cast<std::ptrdiff_t>(std::floor((lo_edge - origin) / width));
  const auto last = static_cast<std::ptrdiff_t>(std::ceil((hi_edge - origin) / width));
  count = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, last - first));
}

double AlignedBins::lo(std::size_t i) const {
  return std::max(lo_edge,
                  origin + static_cast<double>(first + static_cast<std::ptrdiff_t>(i)) * width);
}

double AlignedBins::hi(std::size_t i) const {
  return std::min(hi_edge,
                  origin + static_cast<double>(first + static_cast<std::ptrdiff_t>(i) + 1) * width);
}

std::size_t AlignedBins::bin_of(double v) const {
  const auto i = static_cast<std::ptrdiff_t>(std::floor((v - origin) / width)) - first;
  return static_cast<std::size_t>(
      std::clamp<std::ptrdiff_t>(i, 0, static_cast<std::ptrdiff_t>(count) - 1));
}

std::string quantum_warning(double quantum, const DustCloudOptions& o) {
  // A layer that fills the channel lifts nothing: there is no cloud to resolve.
  if (quantum_resolves(quantum, o.explosible_lower) || !(o.y_end > o.layer_top)) return {};
  const double w = o.filter_width,
               needed = w * std::sqrt(quantum / (kFilterQuantumShare * o.explosible_lower)),
               room = o.y_end - o.layer_top;
  return fmt::format(
      "warning: dust cloud: one parcel alone in a filter box of {:.3g} m "
      "(output.cloud_filter_width) is "
      "{:.3g} kg/m^3, {:.0f} % of output.explosible_lower ({:.3g} kg/m^3), so the filtered "
      "concentration "
      "does not resolve the explosible band's lower edge; a quantum of {:.0f} % of it needs boxes "
      "of {:.3g} m{}",
      w, quantum, 100.0 * quantum / o.explosible_lower, o.explosible_lower,
      100.0 * kFilterQuantumShare, needed,
      needed > room
          ? fmt::format(", more than the {:.3g} m of channel above the layer: lighter parcels "
                        "(particles.parcel_diameter) lower it",
                        room)
          : std::string("; set output.cloud_filter_width to at least that"));
}

double histogram_edge(int k) {
  return kHistogramLow * std::pow(10.0, static_cast<double>(k) / kHistogramPerDecade);
}

namespace {

/// One axis of the filter's lattice: sub-cells of side `step` aligned with `origin`, clipped
/// to [lo, hi], and the positions of a box of `window` consecutive sub-cells (k, or all of
/// them on an axis shorter than the box). An end within a millionth of a step of a lattice
/// line is on it: w / k is rarely exact in floating point, and a sliver sub-cell would make
/// the boxes that hold it narrower than w.
struct LatticeAxis {
  double origin, step, lo_edge, hi_edge;
  std::ptrdiff_t first = 0;  ///< index of the first sub-cell counted from origin
  std::size_t count = 0, window = 0;

  LatticeAxis(double origin_, double step_, double lo_, double hi_, int k)
      : origin(origin_), step(step_), lo_edge(lo_), hi_edge(hi_) {
    if (!(step > 0.0) || !(hi_edge > lo_edge) || k < 1)
      throw std::invalid_argument("dust_cloud: the filter has no box (width or channel)");
    constexpr double kSnap = 1e-6;
    first = static_cast<std::ptrdiff_t>(std::floor((lo_edge - origin) / step + kSnap));
    const auto last = static_cast<std::ptrdiff_t>(std::ceil((hi_edge - origin) / step - kSnap));
    count = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, last - first));
    window = std::min(count, static_cast<std::size_t>(k));
  }
  double lo(std::size_t i) const {
    return i == 0 ? lo_edge
                  : origin + static_cast<double>(first + static_cast<std::ptrdiff_t>(i)) * step;
  }
  double hi(std::size_t i) const {
    return i + 1 == count
               ? hi_edge
               : origin + static_cast<double>(first + static_cast<std::ptrdiff_t>(i) + 1) * step;
  }
  std::size_t bin_of(double v) const {
    const auto i = static_cast<std::ptrdiff_t>(std::floor((v - origin) / step)) - first;
    return static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(i, 0, static_cast<std::ptrdiff_t>(count) - 1));
  }
  std::size_t positions() const { return count - window + 1; }
  /// The box positions p (sub-cells p .. p + window - 1) that hold sub-cell i.
  std::size_t cover(std::size_t i) const {
    const std::size_t last = std::min(i, positions() - 1),
                      first_p = i + 1 >= window ? i + 1 - window : 0;
    return last - first_p + 1;
  }
  /// m, the extent of the box at position p.
  double box_length(std::size_t p) const { return hi(p + window - 1) - lo(p); }
};

/// The filter's lattice over the channel: x from x_start to x_end, y from the layer top to
/// the channel's top, at least one box high (also where the layer fills the channel and
/// nothing can be lifted).
struct FilterLattice {
  LatticeAxis x, y;

  explicit FilterLattice(const DustCloudOptions& o)
      : x(o.x_origin, step(o), o.x_start, o.x_end, o.filter_subcells),
        y(o.layer_top, step(o), o.layer_top, std::max(o.y_end, o.layer_top + o.filter_width),
          o.filter_subcells) {}
  static double step(const DustCloudOptions& o) {
    return o.filter_width / static_cast<double>(o.filter_subcells);
  }
};

/// The part of one lattice axis the boxes holding dust reach: sub-cells first .. first +
/// count - 1 (global indices), which are also the first box positions; `positions` boxes from
/// `first` on hold some of the dust. Arrays span this window, not the whole channel: memory and
/// time follow the cloud's extent, also for boxes much smaller than the channel.
struct AxisWindow {
  std::size_t first = 0, count = 0, positions = 0;
  /// The window for dust in sub-cells lo .. hi.
  AxisWindow(const LatticeAxis& a, std::size_t lo, std::size_t hi)
      : first(lo + 1 >= a.window ? lo + 1 - a.window : 0),
        count(std::min(a.count - 1, hi + a.window - 1) - first + 1),
        positions(std::min(a.positions() - 1, hi) - first + 1) {}
};

int histogram_bin(double c) {
  const int k = static_cast<int>(std::floor(kHistogramPerDecade * std::log10(c / kHistogramLow)));
  return std::clamp(k, 0, kHistogramBins - 1);
}

/// The sums of `in` (sub-cells, x fastest) over every box position, x fastest. Summed box by
/// box, along x and then along y (2k additions per sub-cell), not as differences of prefix
/// sums: a box without dust then sums to exactly zero, where a prefix-sum difference would
/// leave round-off of the whole cloud's mass and count the box as cloud.
void box_sums(const std::vector<double>& in, const FilterLattice& L, const AxisWindow& wx,
              const AxisWindow& wy, std::vector<double>& rows, std::vector<double>& out) {
  const std::size_t nx = wx.count, px = wx.positions, py = wy.positions;
  rows.assign(px * wy.count, 0.0);
  for (std::size_t j = 0; j < wy.count; ++j)
    for (std::size_t p = 0; p < px; ++p) {
      double s = 0.0;
      for (std::size_t i = p; i < p + L.x.window; ++i) s += in[i + nx * j];
      rows[p + px * j] = s;
    }
  out.assign(px * py, 0.0);
  for (std::size_t q = 0; q < py; ++q)
    for (std::size_t p = 0; p < px; ++p) {
      double s = 0.0;
      for (std::size_t j = q; j < q + L.y.window; ++j) s += rows[p + px * j];
      out[p + px * q] = s;
    }
}

/// The band, the cloud and the histogram from the lifted parcels' sub-cells: each sub-cell's
/// mass shared equally among the n box positions that hold it, each box's share counted at
/// its concentration (its area: share / concentration).
void fill_filtered(const FilterLattice& L, DustCloudScratch& s, const DustCloudOptions& o,
                   FilteredCloud& f) {
  f.explosible_x_min = f.explosible_x_max = kNaN;
  if (s.lifted_ix.empty()) {
    f.cloud_concentration = f.fines_cloud_concentration = kNaN;
    f.explosible_concentration = f.fines_explosible_concentration = kNaN;
    return;
  }
  const auto [x_lo, x_hi] = std::minmax_element(s.lifted_ix.begin(), s.lifted_ix.end());
  const auto [y_lo, y_hi] = std::minmax_element(s.lifted_iy.begin(), s.lifted_iy.end());
  const AxisWindow wx(L.x, *x_lo, *x_hi), wy(L.y, *y_lo, *y_hi);
  const std::size_t size = wx.count * wy.count;
  s.cell_mass.assign(size, 0.0);
  s.cell_fines.assign(size, 0.0);
  // In parcel order, as every sum here: the same parcels give the same bits.
  for (std::size_t k = 0; k < s.lifted_ix.size(); ++k) {
    const std::size_t cell = (s.lifted_ix[k] - wx.first) + wx.count * (s.lifted_iy[k] - wy.first);
    s.cell_mass[cell] += s.lifted_mass[k];
    s.cell_fines[cell] += s.lifted_fines[k];
  }
  s.shares.resize(size);
  s.fine_shares.resize(size);
  for (std::size_t j = 0; j < wy.count; ++j)
    for (std::size_t i = 0; i < wx.count; ++i) {
      const std::size_t k = i + wx.count * j;
      const auto n = static_cast<double>(L.x.cover(wx.first + i) * L.y.cover(wy.first + j));
      s.shares[k] = s.cell_mass[k] / n;
      s.fine_shares[k] = s.cell_fines[k] / n;
    }
  box_sums(s.cell_mass, L, wx, wy, s.rows, s.box_mass);
  box_sums(s.shares, L, wx, wy, s.rows, s.box_share);
  box_sums(s.fine_shares, L, wx, wy, s.rows, s.box_fines);
  double cloud_mass = 0.0;
  const std::size_t px = wx.positions;
  for (std::size_t q = 0; q < wy.positions; ++q) {
    for (std::size_t p = 0; p < px; ++p) {
      const std::size_t b = p + px * q;
      const double mass = s.box_mass[b];
      if (!(mass > 0.0)) continue;
      const std::size_t gp = wx.first + p, gq = wy.first + q;  // the box's lattice position
      const double c = mass / (L.x.box_length(gp) * L.y.box_length(gq)), share = s.box_share[b],
                   fines = s.box_fines[b], area = share / c;
      f.cloud_area += area;
      cloud_mass += share;
      const auto bin = static_cast<std::size_t>(histogram_bin(c));
      f.histogram_mass[bin] += share;
      f.histogram_fines[bin] += fines;
      f.histogram_area[bin] += area;
      if (!(c >= o.explosible_lower && c <= o.explosible_upper)) continue;
      f.explosible_mass += share;
      f.fines_explosible_mass += fines;
      f.explosible_area += area;
      const double x_lo = L.x.lo(gp), x_hi = L.x.hi(gp + L.x.window - 1);
      f.explosible_x_min =
          std::isnan(f.explosible_x_min) ? x_lo : std::min(f.explosible_x_min, x_lo);
      f.explosible_x_max =
          std::isnan(f.explosible_x_max) ? x_hi : std::max(f.explosible_x_max, x_hi);
    }
  }
  f.cloud_concentration = f.cloud_area > 0.0 ? cloud_mass / f.cloud_area : kNaN;
  f.fines_cloud_concentration = f.cloud_area > 0.0 ? f.fines_lifted_mass / f.cloud_area : kNaN;
  const bool band = f.explosible_area > 0.0;
  f.explosible_concentration = band ? f.explosible_mass / f.explosible_area : kNaN;
  f.fines_explosible_concentration = band ? f.fines_explosible_mass / f.explosible_area : kNaN;
}

void check_shapes(const CloudParcels& p, const CloudField& f) {
  const std::size_t n = p.x.size();
  if (p.y.size() != n || p.mass.size() != n || p.temperature.size() != n ||
      (!p.size_class.empty() && p.size_class.size() != n) ||
      (!p.particle_diameter.empty() && p.particle_diameter.size() != n))
    throw std::invalid_argument("dust_cloud: the parcel columns differ in length");
  if (f.x_faces.size() < 2 || f.y_faces.size() < 2)
    throw std::invalid_argument("dust_cloud: the field has no cells");
  if (f.concentration.size() != (f.x_faces.size() - 1) * (f.y_faces.size() - 1))
    throw std::invalid_argument("dust_cloud: the concentration does not hold nx * ny values");
}

/// The lifted columns: the most downstream one and the one holding the most mass.
void find_lifted_columns(std::span<const double> x_faces, const std::vector<double>& column_mass,
                         DustCloud& cloud) {
  cloud.first_lifted_x = cloud.densest_lifted_x = kNaN;
  double densest = 0.0;
  for (std::size_t i = 0; i < column_mass.size(); ++i) {
    if (!(column_mass[i] > 0.0)) continue;
    const double centre = 0.5 * (x_faces[i] + x_faces[i + 1]);
    cloud.first_lifted_x = centre;
    if (column_mass[i] > densest) {
      densest = column_mass[i];
      cloud.densest_lifted_x = centre;
    }
  }
}

/// The cloud's top on the flow grid: the highest row above the layer that reaches the level.
void find_cloud_top(const CloudField& f, const DustCloudOptions& o, DustCloud& cloud) {
  const std::size_t nx = f.x_faces.size() - 1, ny = f.y_faces.size() - 1;
  for (std::size_t j = 0; j < ny; ++j) {
    if (!(0.5 * (f.y_faces[j] + f.y_faces[j + 1]) > o.layer_top)) continue;
    for (std::size_t i = 0; i < nx; ++i) {
      if (f.concentration[i + nx * j] >= o.top_concentration) {
        cloud.cloud_top = f.y_faces[j + 1] - o.layer_top;
        break;
      }
    }
  }
}

}  // namespace

DustCloud dust_cloud(const CloudParcels& p, const CloudField& f, const DustCloudOptions& o,
                     DustCloudScratch& scratch) {
  check_shapes(p, f);
  const std::size_t n = p.x.size();
  const std::size_t nx = f.x_faces.size() - 1;
  const int classes = std::max(1, o.classes);
  const FilterLattice lattice(o);

  DustCloud cloud;
  std::vector<LiftedSample> sample(static_cast<std::size_t>(classes) + 1);  // the last: all
  LiftedSample& all = sample.back();
  scratch.column_mass.assign(nx, 0.0);
  for (auto* v : {&scratch.lifted_ix, &scratch.lifted_iy}) v->clear();
  for (auto* v : {&scratch.lifted_mass, &scratch.lifted_fines}) v->clear();
  cloud.mass_above.assign(o.heights.size(), 0.0);
  double largest = 0.0;
  const double lifted_above = o.layer_top + o.lift_height;
  for (std::size_t i = 0; i < n; ++i) {
    const double c = p.size_class.empty() ? 0.0 : p.size_class[i];
    if (!(c >= 0.0 && c < classes))
      throw std::invalid_argument("dust_cloud: parcel size class " + std::to_string(c) +
                                  " is not one of the " + std::to_string(classes) + " classes");
    largest = std::max(largest, p.mass[i]);
    for (std::size_t k = 0; k < o.heights.size(); ++k)
      if (p.y[i] > o.layer_top + o.heights[k]) cloud.mass_above[k] += p.mass[i];
    LiftedSample& mine = sample[static_cast<std::size_t>(c)];
    if (!(p.y[i] > lifted_above)) {
      mine.resting += p.mass[i];
      all.resting += p.mass[i];
      continue;
    }
    for (LiftedSample* s : {&mine, &all}) {
      s->height.push_back(p.y[i] - o.layer_top);
      s->mass.push_back(p.mass[i]);
      s->temperature_max = std::max(s->temperature_max, p.temperature[i]);
      s->heat += p.mass[i] * p.temperature[i];
    }
    scratch.column_mass[column_of(f.x_faces, p.x[i])] += p.mass[i];
    // The filtered concentration counts the lifted dust only: the bed is what is not lifted.
    const bool fine = !p.particle_diameter.empty() && p.particle_diameter[i] < o.fines_diameter;
    if (fine) cloud.filtered.fines_lifted_mass += p.mass[i];
    scratch.lifted_ix.push_back(lattice.x.bin_of(p.x[i]));
    scratch.lifted_iy.push_back(lattice.y.bin_of(p.y[i]));
    scratch.lifted_mass.push_back(p.mass[i]);
    scratch.lifted_fines.push_back(fine ? p.mass[i] : 0.0);
  }

  std::vector<std::size_t> order;
  cloud.all = all.summary(order);
  for (int k = 0; k < classes; ++k)
    cloud.per_class.push_back(sample[static_cast<std::size_t>(k)].summary(order));
  cloud.filtered.quantum = concentration_quantum(largest, o.filter_width);
  fill_filtered(lattice, scratch, o, cloud.filtered);

  find_lifted_columns(f.x_faces, scratch.column_mass, cloud);
  find_cloud_top(f, o, cloud);
  return cloud;
}

}  // namespace dustlift
