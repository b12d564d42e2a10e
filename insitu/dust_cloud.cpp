#include "insitu/dust_cloud.hpp"

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

DustCloud dust_cloud(const CloudParcels& p, const CloudField& f, const DustCloudOptions& o,
                     std::vector<double>& column_mass) {
  const std::size_t n = p.x.size();
  if (p.y.size() != n || p.mass.size() != n || p.temperature.size() != n ||
      (!p.size_class.empty() && p.size_class.size() != n))
    throw std::invalid_argument("dust_cloud: the parcel columns differ in length");
  if (f.x_faces.size() < 2 || f.y_faces.size() < 2)
    throw std::invalid_argument("dust_cloud: the field has no cells");
  const std::size_t nx = f.x_faces.size() - 1, ny = f.y_faces.size() - 1;
  if (f.concentration.size() != nx * ny)
    throw std::invalid_argument("dust_cloud: the concentration does not hold nx * ny values");
  const int classes = std::max(1, o.classes);

  std::vector<LiftedSample> sample(static_cast<std::size_t>(classes) + 1);  // the last: all
  LiftedSample& all = sample.back();
  column_mass.assign(nx, 0.0);
  const double lifted_above = o.layer_top + o.lift_height;
  for (std::size_t i = 0; i < n; ++i) {
    const double c = p.size_class.empty() ? 0.0 : p.size_class[i];
    if (!(c >= 0.0 && c < classes))
      throw std::invalid_argument("dust_cloud: parcel size class " + std::to_string(c) +
                                  " is not one of the " + std::to_string(classes) + " classes");
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
    column_mass[column_of(f.x_faces, p.x[i])] += p.mass[i];
  }

  DustCloud cloud;
  std::vector<std::size_t> order;
  cloud.all = all.summary(order);
  for (int k = 0; k < classes; ++k)
    cloud.per_class.push_back(sample[static_cast<std::size_t>(k)].summary(order));

  // The lifted columns: the most downstream one and the one holding the most mass.
  cloud.first_lifted_x = cloud.densest_lifted_x = kNaN;
  double densest = 0.0;
  for (std::size_t i = 0; i < nx; ++i) {
    if (!(column_mass[i] > 0.0)) continue;
    const double centre = 0.5 * (f.x_faces[i] + f.x_faces[i + 1]);
    cloud.first_lifted_x = centre;
    if (column_mass[i] > densest) {
      densest = column_mass[i];
      cloud.densest_lifted_x = centre;
    }
  }

  // The concentration above the layer: the cloud's top and its explosible part.
  cloud.explosible_x_min = cloud.explosible_x_max = kNaN;
  for (std::size_t j = 0; j < ny; ++j) {
    if (!(0.5 * (f.y_faces[j] + f.y_faces[j + 1]) > o.layer_top)) continue;
    const double dy = f.y_faces[j + 1] - f.y_faces[j];
    bool reaches_edge = false;
    for (std::size_t i = 0; i < nx; ++i) {
      const double c = f.concentration[i + nx * j];
      reaches_edge = reaches_edge || c >= o.edge_concentration;
      if (!(c >= o.explosible_concentration)) continue;
      cloud.explosible_area += (f.x_faces[i + 1] - f.x_faces[i]) * dy;
      cloud.explosible_x_min = std::isnan(cloud.explosible_x_min)
                                   ? f.x_faces[i]
                                   : std::min(cloud.explosible_x_min, f.x_faces[i]);
      cloud.explosible_x_max = std::isnan(cloud.explosible_x_max)
                                   ? f.x_faces[i + 1]
                                   : std::max(cloud.explosible_x_max, f.x_faces[i + 1]);
    }
    if (reaches_edge) cloud.cloud_top = f.y_faces[j + 1] - o.layer_top;
  }
  return cloud;
}

}  // namespace dustlift
