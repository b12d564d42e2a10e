#pragma once
// Dust layer generator: fills the layer rectangle with parcels at a target areal
// fraction, reproducibly and without initial overlaps, in one of the arrangements of
// LayerArrangement (docs/dem.md, "Layer structures"), or places the parcels of a layer
// file; then builds the scene's ParcelSystem.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/dem/dem_config.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {

/// The sites of a generated layer: rows x cols, pitch >= parcel diameter.
/// Hexagonal: even rows (0, 2, ...) hold cols sites, odd rows cols - 1 (shifted by pitch_x / 2).
struct LayerLattice {
  /// Parcels placed without a loose top (real_per_parcel is derived from it).
  std::int64_t n_parcels = 0;
  int rows = 0, cols = 0;
  double pitch_x = 0.0, pitch_y = 0.0;  ///< m (hexagonal: pitch_y is the row spacing)
};

/// Rectangular lattice (lattice, jittered_lattice, settled): n = round(fraction * area /
/// disc area) parcels on the row count that maximises the smaller pitch (sites beyond n
/// stay empty). Throws std::invalid_argument if the fraction cannot be placed without
/// overlap (above about pi/4) or the layer is thinner than a parcel.
LayerLattice plan_layer_lattice(const LayerConfig& layer, double parcel_d);

/// Columnar: floor(depth / D) rows at vertical pitch D (touching, the bottom row on the
/// floor), cols = round(n / rows) columns at pitch width / cols. Throws if pitch_x < D.
LayerLattice plan_columnar_layer(const LayerConfig& layer, double parcel_d);

/// Hexagonal: among row counts with row spacing depth / rows >= D, the one whose nearest
/// centre distance (min of pitch_x and the diagonal to the offset row) is largest, with the
/// column count that makes the parcel count nearest n. Throws if that distance is below D.
LayerLattice plan_hexagonal_layer(const LayerConfig& layer, double parcel_d);

/// The plan of layer.arrangement (throws std::invalid_argument for File: no plan).
LayerLattice plan_layer(const LayerConfig& layer, double parcel_d);

/// Smallest centre distance between parcels of a plan (and twice the gap to the floor
/// for columnar, whose rows touch): what "no overlap" is checked against.
double plan_nearest_distance(const LayerConfig& layer, const LayerLattice& plan);

/// Whether site `column` of row `row` (of `rows`, counted from the floor) holds a parcel:
/// every site below the loose top rows; in them ceil((column + 1) f) > ceil(column f), which
/// keeps the first site and ceil(n f) of any n sites, evenly spread (f = 1/2: every other).
bool layer_site_kept(const LayerConfig& layer, int rows, int row, int column);

/// Parcel centres of the layer (x, y), row by row from the bottom left; the sites of a
/// loose top (layer_site_kept) left out.
struct LayerPositions {
  LayerLattice lattice;
  std::vector<double> x, y;
};
LayerPositions generate_layer(const LayerConfig& layer, double parcel_d);

/// The size class of each of the `placed` parcels of a generated polydisperse layer, in
/// placement order: largest-remainder counts of the classes' mass fractions, shuffled by the
/// layer's seed (solver/dem/size_distribution.hpp).
std::vector<int> layer_size_classes(const DemConfig& cfg, std::size_t placed);

/// "size classes (...)": each class's real diameter, parcel count and mass fraction ("" for
/// a monodisperse layer).
std::string describe_size_classes(const DemConfig& cfg);

/// One line for `dustlift info` and the run log: arrangement, rows x columns, pitches,
/// parcel count and areal fraction (or the file's parcel count), and the size classes.
std::string describe_layer(const DemConfig& cfg);

/// One line about the bed a system holds: its highest parcel top (m) and the areal
/// fraction of the parcels between the floor (layer.y_min) and that top, over the layer's
/// width (for settled beds, whose top is only known after settling).
std::string describe_bed(const ParcelSystem& system, const LayerConfig& layer);

/// Builds the ParcelSystem of a scene: the generated layer at rest (or the file's parcels),
/// real particles per parcel from cfg.real_per_parcel (the parser derives it), and settles
/// it under gravity when layer_settles().
ParcelSystem make_layer_system(const DemConfig& cfg);

/// Lets a bed settle under gravity g (m/s^2, downwards) until its kinetic energy per
/// parcel falls below `ke_per_parcel` J/m or `max_time` s has passed; then zeroes the
/// velocities. Returns the simulated time used.
double settle_under_gravity(ParcelSystem& system, double g, double ke_per_parcel, double max_time);

/// Uniform double in [0, 1) from a 64-bit state (splitmix64): portable, unlike the
/// standard distributions, so a seed gives the same layer on every platform.
double uniform_from_seed(std::uint64_t& state);

}  // namespace dustlift
