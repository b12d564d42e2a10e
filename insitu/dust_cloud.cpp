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
      "warning: dust cloud: one parcel alone in a filter cell of {:.3g} m "
      "(output.cloud_filter_width) is "
      "{:.3g} kg/m^3, {:.0f} % of output.explosible_lower ({:.3g} kg/m^3), so the filtered "
      "concentration "
      "does not resolve the explosible band's lower edge; a quantum of {:.0f} % of it needs cells "
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

/// The filter's cells: squares of side w aligned with x_origin and the layer top, clipped to
/// the channel.
struct FilterCells {
  AlignedBins x, y;
  std::size_t nx, ny;

  explicit FilterCells(const DustCloudOptions& o)
      : x(o.x_origin, o.filter_width, o.x_start, o.x_end),
        // At least one row, also where the layer fills the channel (nothing can be lifted).
        y(o.layer_top, o.filter_width, o.layer_top,
          std::max(o.y_end, o.layer_top + o.filter_width)),
        nx(x.count),
        ny(y.count) {}
  double area(std::size_t i, std::size_t j) const { return x.length(i) * y.length(j); }
  std::size_t cell_of(double px, double py) const { return x.bin_of(px) + nx * y.bin_of(py); }
};

int histogram_bin(double c) {
  const int k = static_cast<int>(std::floor(kHistogramPerDecade * std::log10(c / kHistogramLow)));
  return std::clamp(k, 0, kHistogramBins - 1);
}

/// The band, the cloud and the histogram from the cells' lifted and fine masses.
void fill_filtered(const FilterCells& cells, const std::vector<double>& mass,
                   const std::vector<double>& fines, const DustCloudOptions& o, FilteredCloud& f) {
  f.explosible_x_min = f.explosible_x_max = kNaN;
  double cloud_mass = 0.0;
  for (std::size_t j = 0; j < cells.ny; ++j) {
    for (std::size_t i = 0; i < cells.nx; ++i) {
      const std::size_t k = i + cells.nx * j;
      if (!(mass[k] > 0.0)) continue;
      const double area = cells.area(i, j), c = mass[k] / area;
      f.cloud_area += area;
      cloud_mass += mass[k];
      const auto bin = static_cast<std::size_t>(histogram_bin(c));
      f.histogram_mass[bin] += mass[k];
      f.histogram_fines[bin] += fines[k];
      f.histogram_area[bin] += area;
      if (!(c >= o.explosible_lower && c <= o.explosible_upper)) continue;
      f.explosible_mass += mass[k];
      f.fines_explosible_mass += fines[k];
      f.explosible_area += area;
      f.explosible_x_min = std::isnan(f.explosible_x_min)
                               ? cells.x.lo(i)
                               : std::min(f.explosible_x_min, cells.x.lo(i));
      f.explosible_x_max = std::isnan(f.explosible_x_max)
                               ? cells.x.hi(i)
                               : std::max(f.explosible_x_max, cells.x.hi(i));
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
  const FilterCells cells(o);

  DustCloud cloud;
  std::vector<LiftedSample> sample(static_cast<std::size_t>(classes) + 1);  // the last: all
  LiftedSample& all = sample.back();
  scratch.column_mass.assign(nx, 0.0);
  scratch.cell_mass.assign(cells.nx * cells.ny, 0.0);
  scratch.cell_fines.assign(cells.nx * cells.ny, 0.0);
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
    const std::size_t cell = cells.cell_of(p.x[i], p.y[i]);
    scratch.cell_mass[cell] += p.mass[i];
    if (!p.particle_diameter.empty() && p.particle_diameter[i] < o.fines_diameter) {
      scratch.cell_fines[cell] += p.mass[i];
      cloud.filtered.fines_lifted_mass += p.mass[i];
    }
  }

  std::vector<std::size_t> order;
  cloud.all = all.summary(order);
  for (int k = 0; k < classes; ++k)
    cloud.per_class.push_back(sample[static_cast<std::size_t>(k)].summary(order));
  cloud.filtered.quantum = concentration_quantum(largest, o.filter_width);
  fill_filtered(cells, scratch.cell_mass, scratch.cell_fines, o, cloud.filtered);

  find_lifted_columns(f.x_faces, scratch.column_mass, cloud);
  find_cloud_top(f, o, cloud);
  return cloud;
}

}  // namespace dustlift
