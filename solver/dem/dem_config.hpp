#pragma once
// Settings of the DEM parcel system, as resolved from a scene (SI units).
// Owned by the DEM module; parsed in solver/scene/parse_particles.cpp, where every
// default below is also written into the resolved scene. Paper values: Table 2 and
// docs/dem.md; the garbled or missing items are documented in docs/dem.md.
#include <array>
#include <cstdint>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include "solver/laws/cohesion.hpp"
#include "solver/laws/contact.hpp"

namespace dustlift {

/// How the layer generator places parcels in the layer rectangle (docs/dem.md, "Layer
/// structures", says what each implies for contacts and force chains at t = 0).
enum class LayerArrangement {
  Lattice,          ///< rectangular lattice, parcels at the site centres
  JitteredLattice,  ///< same lattice, each parcel moved randomly inside its free play
  Columnar,         ///< floor(depth / D) rows touching vertically, columns spaced to the fraction
  Hexagonal,        ///< offset rows (odd rows shifted by half a pitch), no contact
  Settled,          ///< the jittered lattice, then settled under gravity and brought to rest
  File,             ///< parcels read from a CSV file (DemConfig::layer_parcels)
};

/// Scene names of the arrangements (`[particles.layer] arrangement`).
inline constexpr std::array<std::pair<std::string_view, LayerArrangement>, 6>
    kLayerArrangementNames{{
        {"jittered_lattice", LayerArrangement::JitteredLattice},
        {"lattice", LayerArrangement::Lattice},
        {"columnar", LayerArrangement::Columnar},
        {"hexagonal", LayerArrangement::Hexagonal},
        {"settled", LayerArrangement::Settled},
        {"file", LayerArrangement::File},
    }};

inline std::string_view layer_arrangement_name(LayerArrangement a) {
  for (const auto& [name, value] : kLayerArrangementNames)
    if (value == a) return name;
  return "?";
}

/// One parcel placed by a layer file (arrangement = file), SI units.
struct PlacedParcel {
  double x = 0.0, y = 0.0;     ///< m, centre
  double diameter = 100e-6;    ///< m, parcel diameter
  double vx = 0.0, vy = 0.0;   ///< m/s
  double omega = 0.0;          ///< rad/s, counter-clockwise positive
  double temperature = 300.0;  ///< K
  /// m, the real particles' diameter (optional column `particle_diameter`; 0: not given,
  /// particles.diameter). The file's distinct values are its size classes.
  double particle_diameter = 0.0;
};

/// The rectangle the generator fills with parcels.
struct LayerConfig {
  double x_min = 0.0, x_max = 0.4;     ///< m
  double y_min = -0.002, y_max = 0.0;  ///< m (surface at y = 0, floor at -2 mm)
  double volume_fraction = 0.59;       ///< alpha_p; the parcels' areal fraction equals it
  std::uint64_t seed = 1;
  LayerArrangement arrangement = LayerArrangement::JitteredLattice;
  bool settle = false;  ///< let the layer settle under gravity before t = 0
  // A looser top (generated arrangements): the top `loose_top_rows` rows keep only the share
  // `loose_top_fill` of their sites, evenly spread (docs/dem.md, "A looser top"). The rows
  // below stay at volume_fraction, which real_per_parcel is derived from.
  int loose_top_rows = 0;
  double loose_top_fill = 1.0;
  // Columns of one class each (particles.parcel_ratio with a size distribution) side by side,
  // every parcel touching its neighbours (the real particles per parcel hold volume_fraction),
  // or, when false, spread to hold volume_fraction in their discs: gaps of a size set by the
  // parcels, which made the lifted mass depend on them (docs/dem.md, "Parcels per class").
  bool touching_columns = true;
};

/// Whether the layer is settled under gravity before t = 0 (`settle`, or arrangement = settled).
inline bool layer_settles(const LayerConfig& layer) {
  return layer.settle || layer.arrangement == LayerArrangement::Settled;
}

/// The region the neighbour cells cover and its walls (axis-aligned planes at its edges).
/// Parcels may leave the region; they are then binned into its edge cells (correct, slower).
struct DemDomain {
  double x_min = 0.0, x_max = 0.4;      ///< m
  double y_min = -0.002, y_max = 0.02;  ///< m
  bool wall_bottom = true;              ///< the floor
  bool wall_top = false;
  bool wall_left = false;
  bool wall_right = false;
  bool periodic_x = false;  ///< x_min and x_max identified (no left/right walls)
};

/// One size class of a polydisperse layer: real particles of one diameter holding a share of
/// the layer's solid mass.
struct SizeClass {
  double diameter = 100e-6;    ///< m, real particle diameter
  double mass_fraction = 1.0;  ///< share of the layer's mass (the classes' shares sum to 1)
  /// m, the class's own parcel diameter (particles.parcel_ratio times `diameter`); 0: the
  /// layer's one DemConfig::parcel_diameter.
  double parcel_diameter = 0.0;
};

/// Whether the classes have parcels of their own sizes (particles.parcel_ratio with a size
/// distribution): the layer is then packed in columns of one class each (class_columns.hpp).
inline bool has_class_parcels(const std::vector<SizeClass>& classes) {
  for (const SizeClass& c : classes)
    if (c.parcel_diameter > 0.0) return true;
  return false;
}

struct DemConfig {
  bool enabled = false;  ///< false: a gas-only scene, no parcel code runs
  /// The scene says `enabled = false` (e.g. `--set particles.enabled=false`): the dust is
  /// switched off on purpose, and the settings that only concern it are left unread.
  bool switched_off = false;

  // Real particles (Table 2).
  double particle_diameter = 100e-6;   ///< m
  double density = 980.0;              ///< kg/m^3
  double heat_capacity = 1200.0;       ///< J/(kg K)
  double initial_temperature = 300.0;  ///< K
  /// A polydisperse layer's size classes, smallest first (empty: one class of
  /// particle_diameter). Every class shares the parcel diameter.
  std::vector<SizeClass> size_classes;

  // Coarse graining (eq. 11, §4): parcel diameter n_xy d; real particles per parcel per
  // metre of depth n_i = n_xy^2 n_z. Zero means derived from the layer: alpha_p A / (N V_p).
  double parcel_diameter = 100e-6;  ///< m
  double real_per_parcel = 0.0;     ///< 1/m (per metre of depth); 0: derived

  LayerConfig layer;
  /// arrangement = file: the parcels, in file order. Parcel i holds
  /// real_per_parcel (D_i / parcel_diameter)^2 real particles (eq. 11, n_xy^2 n_z).
  std::vector<PlacedParcel> layer_parcels;
  ContactParams contact;       ///< parcel–parcel
  ContactParams wall_contact;  ///< parcel–wall (defaults to `contact`)
  /// Van der Waals cohesion per real pair (off unless the scene sets [particles.cohesion]).
  CohesionParams cohesion;
  CohesionParams wall_cohesion;  ///< a particle and a wall (defaults to `cohesion`)
  DemDomain domain;

  double courant = 0.1;                     ///< nu_DEM of eq. (18): dt = nu sqrt(m / max(k_n, k_t))
  double gravity_x = 0.0, gravity_y = 0.0;  ///< m/s^2; the paper has no gravity (eq. 5)
  double skin = 0.1;                        ///< neighbour-list skin, in parcel diameters
  /// A fast parcel's skin covers this many sub-steps at its speed (at least skin / 2), so
  /// the few fast parcels do not force frequent rebuilds of every parcel's list.
  double fast_skin_substeps = 50.0;
};

}  // namespace dustlift
