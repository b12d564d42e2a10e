#pragma once
// Internal: one parse function per scene section, each in its own file.
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"

namespace dustlift::scene_detail {

void parse_run(TableReader t, RunConfig& run);
void parse_grid(TableReader t, GridConfig& grid);
void parse_gas(TableReader t, GasConfig& gas);
void parse_boundary(TableReader t, BoundaryConfig& b, const ThermoConfig& thermo);
void parse_initial(TableReader t, InitialCondition& ic, const ThermoConfig& thermo);
void parse_particles(TableReader t, DemConfig& dem, const GridConfig& grid, const BoundaryConfig& boundary);
void parse_coupling(TableReader t, CouplingConfig& c, const DemConfig& dem, const GridConfig& grid);
void parse_output(TableReader t, OutputConfig& out, const RunConfig& run, const DemConfig& dem);

/// The smallest cell width of the grid along either axis, m.
double min_cell_width(const GridConfig& grid);

/// A gas state table: p and exactly one of rho or T, optional u, v.
PrimitiveState parse_state(TableReader t, const ThermoConfig& thermo);

/// Checks that need several sections (e.g. periodic boundaries come in pairs).
void check_cross_section(const Scene& s);

}  // namespace dustlift::scene_detail
