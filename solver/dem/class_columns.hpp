#pragma once
// A polydisperse layer whose size classes have parcels of their own sizes
// (particles.parcel_ratio: class k's parcels are ratio_k d_k wide): columns of touching parcels
// of one class each, the columns of the classes interleaved along the layer by the layer's
// seed (docs/dem.md, "Parcels per class"). Each column's top parcel touches the layer top, so
// every class meets the flow at the same surface; a column of class k holds
// rows_k = floor(depth / D_k) parcels and is as wide as puts the layer's volume fraction in it.
// Pure functions: the parser checks and describes the plan the generator then places.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/dem/dem_config.hpp"

namespace dustlift {

/// A layer the columns cannot pack: a class that rounds to no column, or (too_dense) columns
/// narrower than their parcels.
struct ClassColumnsError : std::invalid_argument {
  ClassColumnsError(const std::string& what, bool dense)
      : std::invalid_argument(what), too_dense(dense) {}
  bool too_dense;
};

struct ClassColumns {
  std::vector<int> rows;                ///< per class: parcels in one column
  std::vector<std::int64_t> columns;    ///< per class: its columns
  std::vector<double> width;            ///< per class: one column's width, m
  std::vector<double> real_per_parcel;  ///< per class: real particles per parcel per metre
  std::vector<int> order;               ///< the class of each column, from x_min on
  std::int64_t parcels = 0;             ///< in the whole layer
  double stretch = 1.0;  ///< the columns' widths over the widths at the exact volume fraction
};

/// The plan of a layer whose classes have their own parcel diameters
/// (SizeClass::parcel_diameter > 0 for every class): for class k of parcel diameter D_k, rows_k
/// parcels a column; the width w_k = rows_k (pi D_k^2 / 4) / (alpha_p depth) that holds
/// alpha_p; round(f_k W / w_k) columns (f_k its mass fraction, W the layer's width); all widths
/// stretched by W / sum(columns w) so the columns fill the layer; each parcel of class k holds
/// n_k = alpha_p w_k depth / (rows_k V_p(d_k)) real particles, so the layer's 3-D solid
/// fraction is alpha_p and class k's share of the mass is its columns' share of the width.
/// With LayerConfig::touching_columns, w_k = D_k (columns side by side, every parcel touching
/// its neighbours; a column dropped from the class most over its share while they would not
/// fit), and n_k, the same formula, puts alpha_p in the layer's real particles.
/// Throws ClassColumnsError when a class rounds to no column or its columns would be narrower
/// than its parcels (a fraction above pi/4 rows_k D_k / depth).
ClassColumns plan_class_columns(const DemConfig& cfg);

/// The centres (m) and classes of the plan's parcels, column by column from x_min, each
/// column from the top down.
struct ClassColumnParcels {
  std::vector<double> x, y;
  std::vector<int> size_class;
};
ClassColumnParcels place_class_columns(const DemConfig& cfg, const ClassColumns& plan);

/// One line: each class's parcel diameter, rows, columns, parcels and mass share.
std::string describe_class_columns(const DemConfig& cfg, const ClassColumns& plan);

}  // namespace dustlift
