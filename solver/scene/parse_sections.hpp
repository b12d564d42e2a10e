#pragma once
// Internal: one parse function per scene section, each in its own file.
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"

namespace dustlift::scene_detail {

/// Smallest CFL number and DEM Courant number accepted: below, a run takes more than a
/// thousand times the steps of a usual value and gains no stability.
inline constexpr double kMinCourant = 1e-3;
/// Relative tolerance of size comparisons against grid cells: a cell computed as 2.0 / 1000
/// comes out a rounding smaller than the 0.002 m parcel that is meant to fit it.
inline constexpr double kCellTolerance = 1e-9;

/// The floor a layer thickness sets (particles.layer.thickness): the layer's bottom
/// y_max - thickness, which is particles.layer.y_min and grid.y.start unless given.
struct LayerFloor {
  double y = 0.0;          ///< m, the floor: y_max - thickness
  double thickness = 0.0;  ///< m
  double y_max = 0.0;      ///< m, the layer's top
};
/// particles.layer.thickness and y_max when the scene gives a thickness (else nothing); read
/// before the grid, whose floor follows it.
std::optional<LayerFloor> read_layer_floor(TableReader& root);
/// Whether a given y agrees with the floor the thickness sets (to rounding).
bool agrees_with_floor(double y, const LayerFloor& floor);

void parse_run(TableReader t, RunConfig& run);
void parse_grid(TableReader t, GridConfig& grid, const std::optional<LayerFloor>& floor);
void parse_gas(TableReader t, GasConfig& gas);
void parse_boundary(TableReader t, BoundaryConfig& b, const ThermoConfig& thermo);
void parse_initial(TableReader t, InitialCondition& ic, const ThermoConfig& thermo,
                   const GridConfig& grid);
/// `larger_than_cells`: particles may be larger than the cells (a one-way run that averages the
/// undisturbed flow over each particle, coupling.finite_size).
void parse_particles(TableReader t, DemConfig& dem, const GridConfig& grid,
                     const BoundaryConfig& boundary, bool larger_than_cells = false);
/// [particles.cohesion]: van der Waals cohesion per real pair (off without the table).
void parse_cohesion(TableReader t, DemConfig& dem);
void parse_coupling(TableReader t, CouplingConfig& c, const DemConfig& dem, const GridConfig& grid);
void parse_output(TableReader t, OutputConfig& out, const RunConfig& run, const DemConfig& dem,
                  const GridConfig& grid);
void parse_insitu(TableReader t, InsituConfig& insitu);

/// [particles.size_distribution] read: its classes, and the keys its errors name (the one
/// setting the class sizes and the one setting their shares).
struct SizeDistribution {
  std::vector<SizeClass> classes;
  double mass_median =
      0.0;  ///< m: the log-normal median, or the discrete classes' (mass_median_diameter)
  const char* size_key = "diameters";
  const char* count_key = "mass_fractions";
};
/// Reads the table (either form; refuses fractions not summing to 1, sigma_g <= 1, diameters
/// not ascending or not positive, lists of different lengths) and notes a log-normal cut's
/// classes in the resolved scene.
SizeDistribution parse_size_distribution(TableReader& sd);
/// Refuses a class larger than the smallest cell, the layer's depth or the parcel diameter.
void check_class_sizes(const SizeDistribution& dist, const TableReader& sd, const DemConfig& dem,
                       const GridConfig& grid);
/// Refuses a class that gets no parcel of the `placed` parcels (largest-remainder counts).
void check_class_counts(const SizeDistribution& dist, const TableReader& sd, std::int64_t placed);

/// The smallest cell width of the grid along either axis, m.
double min_cell_width(const GridConfig& grid);

/// A gas state table: p and exactly one of rho or T, optional u, v; for thermally perfect air
/// a temperature within the NASA-7 fits.
PrimitiveState parse_state(TableReader t, const ThermoConfig& thermo);

/// Plausibility of a value's unit: a gas pressure below 1 kPa or a temperature below 100 K is
/// refused (naming the key, where it is, the value in Pa or K and what was probably meant)
/// unless the scene sets run.allow_implausible = true (docs/reference/scene-keys.md).
inline constexpr double kPlausiblePressureMin = 1.0e3;     ///< Pa
inline constexpr double kPlausibleTemperatureMin = 100.0;  ///< K
void check_plausible_pressure(TableReader& t, std::string_view key, double p);
void check_plausible_temperature(TableReader& t, std::string_view key, double T);

/// Refuses a temperature outside the fits of thermally perfect air (NASA-7, 200-6000 K),
/// naming `key` of `t`; any positive temperature for a calorically perfect gas.
void check_gas_temperature(TableReader& t, std::string_view key, double T,
                           const ThermoConfig& thermo);

}  // namespace dustlift::scene_detail
