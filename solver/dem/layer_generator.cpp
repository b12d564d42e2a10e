// Dust layer generator (jittered lattice) and the scene's ParcelSystem factory.
#include "solver/dem/layer_generator.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "solver/dem/coarse_graining.hpp"

namespace dustlift {

double uniform_from_seed(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

LayerLattice plan_layer_lattice(const LayerConfig& layer, double parcel_d) {
  const double width = layer.x_max - layer.x_min, height = layer.y_max - layer.y_min;
  if (!(width > 0.0) || !(height > 0.0)) throw std::invalid_argument("layer rectangle is empty");
  if (height < parcel_d || width < parcel_d) {
    throw std::invalid_argument("layer is smaller than one parcel diameter");
  }
  LayerLattice best;
  best.n_parcels = std::llround(layer.volume_fraction * width * height / disc_area(parcel_d));
  if (best.n_parcels < 1) throw std::invalid_argument("layer holds no parcel at this fraction");
  const int max_rows = static_cast<int>(std::floor(height / parcel_d));
  double best_pitch = 0.0;
  for (int rows = 1; rows <= max_rows; ++rows) {
    const std::int64_t cols = (best.n_parcels + rows - 1) / rows;
    const double px = width / static_cast<double>(cols), py = height / rows;
    const double pitch = std::min(px, py);
    if (pitch > best_pitch) {
      best_pitch = pitch;
      best.rows = rows;
      best.cols = static_cast<int>(cols);
      best.pitch_x = px;
      best.pitch_y = py;
    }
  }
  if (best_pitch < parcel_d) {
    throw std::invalid_argument("areal fraction " + std::to_string(layer.volume_fraction) +
                                " cannot be placed on a lattice without overlaps (max about 0.78)");
  }
  return best;
}

LayerPositions generate_layer(const LayerConfig& layer, double parcel_d) {
  LayerPositions out;
  out.lattice = plan_layer_lattice(layer, parcel_d);
  const LayerLattice& L = out.lattice;
  const std::int64_t sites = static_cast<std::int64_t>(L.rows) * L.cols;
  std::uint64_t state = layer.seed;
  // Which sites stay empty: the first (sites - n) of a seeded partial Fisher–Yates shuffle.
  std::vector<char> empty(static_cast<std::size_t>(sites), 0);
  {
    std::vector<std::int64_t> idx(static_cast<std::size_t>(sites));
    std::iota(idx.begin(), idx.end(), std::int64_t{0});
    const std::int64_t n_empty = sites - L.n_parcels;
    for (std::int64_t k = 0; k < n_empty; ++k) {
      const auto r = k + static_cast<std::int64_t>(uniform_from_seed(state) * static_cast<double>(sites - k));
      std::swap(idx[k], idx[std::min(r, sites - 1)]);
      empty[idx[k]] = 1;
    }
  }
  // Free play of a parcel inside its site (a hair less, so neighbours never touch).
  const bool jitter = layer.arrangement == LayerArrangement::JitteredLattice;
  const double play_x = jitter ? 0.999 * (L.pitch_x - parcel_d) : 0.0;
  const double play_y = jitter ? 0.999 * (L.pitch_y - parcel_d) : 0.0;
  out.x.reserve(static_cast<std::size_t>(L.n_parcels));
  out.y.reserve(static_cast<std::size_t>(L.n_parcels));
  for (int r = 0; r < L.rows; ++r) {
    for (int c = 0; c < L.cols; ++c) {
      if (empty[static_cast<std::size_t>(r) * L.cols + c]) continue;
      const double jx = play_x * (uniform_from_seed(state) - 0.5);
      const double jy = play_y * (uniform_from_seed(state) - 0.5);
      out.x.push_back(layer.x_min + (c + 0.5) * L.pitch_x + jx);
      out.y.push_back(layer.y_min + (r + 0.5) * L.pitch_y + jy);
    }
  }
  return out;
}

ParcelSystem make_layer_system(const DemConfig& cfg) {
  const LayerPositions pos = generate_layer(cfg.layer, cfg.parcel_diameter);
  const double area = (cfg.layer.x_max - cfg.layer.x_min) * (cfg.layer.y_max - cfg.layer.y_min);
  const double n_parcels = static_cast<double>(pos.x.size());
  const double n_real = cfg.real_per_parcel > 0.0
                            ? cfg.real_per_parcel
                            : derived_real_per_parcel(cfg.layer.volume_fraction, area, n_parcels,
                                                      cfg.particle_diameter);
  ParcelSystem system(cfg);
  system.reserve(pos.x.size());
  for (std::size_t i = 0; i < pos.x.size(); ++i) {
    ParcelInit p;
    p.x = pos.x[i];
    p.y = pos.y[i];
    p.diameter = cfg.parcel_diameter;
    p.real_diameter = cfg.particle_diameter;
    p.density = cfg.density;
    p.n_real = n_real;
    p.temperature = cfg.initial_temperature;
    system.add_parcel(p);
  }
  if (cfg.layer.settle) {
    // Settle until the bed is quiet: kinetic energy per parcel below a millionth of the
    // work gravity does on one parcel falling one diameter.
    const double m = system.mass.empty() ? 0.0 : system.mass[0];
    const double ke_tol = 1e-6 * m * 9.81 * cfg.parcel_diameter;
    settle_under_gravity(system, 9.81, ke_tol, 1.0);
    // Restart the parcels' history from the settled bed.
    system.x_initial = system.x;
    system.y_initial = system.y;
  }
  return system;
}

double settle_under_gravity(ParcelSystem& system, double g, double ke_per_parcel, double max_time) {
  const double gx = system.config().gravity_x, gy = system.config().gravity_y;
  system.set_gravity(0.0, -g);
  const double chunk = 200.0 * system.stable_time_step();
  const double n = static_cast<double>(std::max<std::size_t>(1, system.size()));
  double t = 0.0;
  // Quiet means slow AND resting on something (a bed that has not started falling is slow too).
  while (t < max_time) {
    system.advance(chunk);
    t += chunk;
    if (system.kinetic_energy() / n < ke_per_parcel && system.contact_pair_count() > 0) break;
  }
  std::fill(system.vx.begin(), system.vx.end(), 0.0);
  std::fill(system.vy.begin(), system.vy.end(), 0.0);
  std::fill(system.omega.begin(), system.omega.end(), 0.0);
  system.set_gravity(gx, gy);
  return t;
}

}  // namespace dustlift
