// Generated layer arrangements: where the sites are (plans) and the parcel centres on them.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"

namespace dustlift {
namespace {

double layer_width(const LayerConfig& layer) { return layer.x_max - layer.x_min; }
double layer_depth(const LayerConfig& layer) { return layer.y_max - layer.y_min; }

/// n = round(fraction * area / disc area), after checking that the rectangle holds a parcel.
std::int64_t target_parcel_count(const LayerConfig& layer, double parcel_d) {
  const double width = layer_width(layer), height = layer_depth(layer);
  if (!(width > 0.0) || !(height > 0.0)) throw std::invalid_argument("layer rectangle is empty");
  if (height < parcel_d || width < parcel_d) {
    throw std::invalid_argument("layer is smaller than one parcel diameter");
  }
  const std::int64_t n = std::llround(layer.volume_fraction * width * height / disc_area(parcel_d));
  if (n < 1) throw std::invalid_argument("layer holds no parcel at this fraction");
  return n;
}

/// The smallest double >= value whose distance from `below` is at least `gap`: touching
/// parcels are placed exactly one diameter apart without a round-off overlap.
double at_least_apart(double value, double below, double gap) {
  while (value - below < gap) value = std::nextafter(value, std::numeric_limits<double>::infinity());
  return value;
}

/// Rectangular lattice sites with a seeded choice of empty sites and optional jitter
/// (today's jittered_lattice; kept bitwise as it was).
void lattice_positions(const LayerConfig& layer, double parcel_d, LayerPositions& out) {
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
  const bool jitter = layer.arrangement == LayerArrangement::JitteredLattice ||
                      layer.arrangement == LayerArrangement::Settled;
  const double play_x = jitter ? 0.999 * (L.pitch_x - parcel_d) : 0.0;
  const double play_y = jitter ? 0.999 * (L.pitch_y - parcel_d) : 0.0;
  for (int r = 0; r < L.rows; ++r) {
    for (int c = 0; c < L.cols; ++c) {
      if (empty[static_cast<std::size_t>(r) * L.cols + c]) continue;
      const double jx = play_x * (uniform_from_seed(state) - 0.5);
      const double jy = play_y * (uniform_from_seed(state) - 0.5);
      // After the draws: the parcels that stay are where they are without a loose top.
      if (!layer_site_kept(layer, L.rows, r, c)) continue;
      out.x.push_back(layer.x_min + (c + 0.5) * L.pitch_x + jx);
      out.y.push_back(layer.y_min + (r + 0.5) * L.pitch_y + jy);
    }
  }
}

/// Columns of touching parcels: the bottom row rests on the floor, each row one diameter
/// above the one below (never less, so no pair starts overlapping).
void columnar_positions(const LayerConfig& layer, double parcel_d, LayerPositions& out) {
  const LayerLattice& L = out.lattice;
  const double radius = 0.5 * parcel_d;
  std::vector<double> row_y(static_cast<std::size_t>(L.rows));
  for (int r = 0; r < L.rows; ++r) {
    const double below = r == 0 ? layer.y_min : row_y[static_cast<std::size_t>(r) - 1];
    const double gap = r == 0 ? radius : parcel_d;
    row_y[static_cast<std::size_t>(r)] = at_least_apart(layer.y_min + radius + r * parcel_d, below, gap);
  }
  for (int r = 0; r < L.rows; ++r) {
    for (int c = 0; c < L.cols; ++c) {
      if (!layer_site_kept(layer, L.rows, r, c)) continue;
      out.x.push_back(layer.x_min + (c + 0.5) * L.pitch_x);
      out.y.push_back(row_y[static_cast<std::size_t>(r)]);
    }
  }
}

/// Offset rows: even rows at (c + 1/2) pitch, odd rows (one site fewer) at (c + 1) pitch.
void hexagonal_positions(const LayerConfig& layer, LayerPositions& out) {
  const LayerLattice& L = out.lattice;
  for (int r = 0; r < L.rows; ++r) {
    const bool odd = r % 2 == 1;
    const int sites = odd ? L.cols - 1 : L.cols;
    for (int c = 0; c < sites; ++c) {
      if (!layer_site_kept(layer, L.rows, r, c)) continue;
      out.x.push_back(layer.x_min + (c + (odd ? 1.0 : 0.5)) * L.pitch_x);
      out.y.push_back(layer.y_min + (r + 0.5) * L.pitch_y);
    }
  }
}

}  // namespace

double uniform_from_seed(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

LayerLattice plan_layer_lattice(const LayerConfig& layer, double parcel_d) {
  const double width = layer_width(layer), height = layer_depth(layer);
  LayerLattice best;
  best.n_parcels = target_parcel_count(layer, parcel_d);
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

LayerLattice plan_columnar_layer(const LayerConfig& layer, double parcel_d) {
  const std::int64_t target = target_parcel_count(layer, parcel_d);
  LayerLattice plan;
  // The relative 1e-12 keeps a depth that is a multiple of D (2 mm / 100 um) from losing
  // its last row to round-off.
  plan.rows = static_cast<int>(std::floor(layer_depth(layer) / parcel_d * (1.0 + 1e-12)));
  plan.cols = static_cast<int>(std::max<std::int64_t>(1, std::llround(static_cast<double>(target) / plan.rows)));
  plan.n_parcels = static_cast<std::int64_t>(plan.rows) * plan.cols;
  plan.pitch_x = layer_width(layer) / plan.cols;
  plan.pitch_y = parcel_d;
  if (plan.pitch_x < parcel_d) {
    throw std::invalid_argument("areal fraction " + std::to_string(layer.volume_fraction) +
                                " needs columns closer than one parcel diameter in a columnar layer (max pi/4 * " +
                                std::to_string(plan.rows) + " D / depth)");
  }
  return plan;
}

LayerLattice plan_hexagonal_layer(const LayerConfig& layer, double parcel_d) {
  const std::int64_t target = target_parcel_count(layer, parcel_d);
  const double width = layer_width(layer), height = layer_depth(layer);
  LayerLattice best;
  double best_nearest = 0.0;
  // Rows at least D apart, as in the lattice: the bottom row then clears the floor and the
  // top row stays inside the rectangle (closer rows would be the same lattice turned 90°).
  const int max_rows = static_cast<int>(std::floor(height / parcel_d));
  for (int rows = 1; rows <= max_rows; ++rows) {
    const int odd_rows = rows / 2, even_rows = rows - odd_rows;
    const auto cols = std::llround(static_cast<double>(target + odd_rows) / rows);
    if (cols < 1 || (odd_rows > 0 && cols < 2)) continue;
    LayerLattice plan;
    plan.rows = rows;
    plan.cols = static_cast<int>(cols);
    plan.n_parcels = even_rows * cols + odd_rows * (cols - 1);
    plan.pitch_x = width / static_cast<double>(cols);
    plan.pitch_y = height / rows;
    LayerConfig hex = layer;
    hex.arrangement = LayerArrangement::Hexagonal;
    const double nearest = plan_nearest_distance(hex, plan);
    if (nearest > best_nearest) {
      best_nearest = nearest;
      best = plan;
    }
  }
  if (best_nearest < parcel_d) {
    throw std::invalid_argument("areal fraction " + std::to_string(layer.volume_fraction) +
                                " cannot be placed on offset rows without overlaps");
  }
  return best;
}

LayerLattice plan_layer(const LayerConfig& layer, double parcel_d) {
  switch (layer.arrangement) {
    case LayerArrangement::Columnar: return plan_columnar_layer(layer, parcel_d);
    case LayerArrangement::Hexagonal: return plan_hexagonal_layer(layer, parcel_d);
    case LayerArrangement::File: throw std::invalid_argument("a layer file has no lattice plan");
    default: return plan_layer_lattice(layer, parcel_d);
  }
}

double plan_nearest_distance(const LayerConfig& layer, const LayerLattice& plan) {
  const double inf = std::numeric_limits<double>::infinity();
  const double px = plan.cols > 1 ? plan.pitch_x : inf;
  if (layer.arrangement != LayerArrangement::Hexagonal) {
    return std::min(px, plan.rows > 1 ? plan.pitch_y : inf);
  }
  const double diagonal = plan.rows > 1 ? std::hypot(0.5 * plan.pitch_x, plan.pitch_y) : inf;
  const double same_column = plan.rows > 2 ? 2.0 * plan.pitch_y : inf;
  return std::min({px, diagonal, same_column});
}

bool layer_site_kept(const LayerConfig& layer, int rows, int row, int column) {
  if (layer.loose_top_rows <= 0 || row < rows - layer.loose_top_rows) return true;
  const double f = layer.loose_top_fill;
  return std::ceil((column + 1) * f) > std::ceil(column * f);
}

LayerPositions generate_layer(const LayerConfig& layer, double parcel_d) {
  LayerPositions out;
  out.lattice = plan_layer(layer, parcel_d);
  out.x.reserve(static_cast<std::size_t>(out.lattice.n_parcels));
  out.y.reserve(static_cast<std::size_t>(out.lattice.n_parcels));
  switch (layer.arrangement) {
    case LayerArrangement::Columnar: columnar_positions(layer, parcel_d, out); break;
    case LayerArrangement::Hexagonal: hexagonal_positions(layer, out); break;
    default: lattice_positions(layer, parcel_d, out); break;
  }
  return out;
}

}  // namespace dustlift
