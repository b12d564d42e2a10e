#pragma once
// The single source of configuration: a typed, validated scene in SI units.
// Every default lives in the parse functions (solver/scene/parse_*.cpp) and is
// written back into `resolved_toml`, which a run stores in its output folder.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "solver/core/grid.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/dem/dem_config.hpp"
#include "solver/gas/gas_config.hpp"
#include "solver/scene/key_fact.hpp"

namespace dustlift {

struct RunConfig {
  std::string name = "run";
  double end_time = 1e-3;          ///< s, simulated
  long long max_steps = 0;         ///< 0: unlimited
  double progress_interval = 2.0;  ///< s of wall time between progress lines
  /// Skip gas cells and parcels that are at rest (off only to check what skipping does, or to
  /// time the difference).
  bool skip_at_rest = true;
  /// Skip only what rests exactly (bitwise the same result as no skipping): rest_tolerance 0.
  bool exact = false;
  /// 0: skip only what rests exactly. > 0 (at most 1e-6): a gas cell rests when |u|, |v| <=
  /// tol sqrt(p/rho) and p, T are within tol (relative) of the resting state, and a parcel
  /// in such gas when its speed, spin and the speed its contact loads would add within a step
  /// are below that velocity and its temperature within tol: the rounding noise that runs
  /// ahead of a shock is then skipped too. Changes results at the level of that noise, well
  /// below what a time step changed by one part in a million changes (docs/performance.md),
  /// and makes long runs 1.6-1.7 times faster: the default. 0 unless skipping within it.
  double rest_tolerance = 1e-10;
  /// Accept values outside the plausible range of their unit (a gas pressure below 1 kPa, a
  /// temperature below 100 K), which are otherwise refused as a probable unit slip.
  bool allow_implausible = false;
  /// Steps between moves of the slab cuts of a run on several MPI ranks (0: never), which
  /// follow the work as the shock moves (docs/parallel.md). No effect on one rank, and none
  /// on the results on any number of ranks.
  long long rebalance_steps = 200;
};

/// A group of parcels chosen by where they started (paper Figs. 10 and 12).
struct BandConfig {
  std::string name;
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;  ///< m, box of initial positions
};

/// A point probe: gas values in the cell holding (x, y), sampled every step or at a cadence
/// (OpenFOAM's `probes`): series probes, columns <name>_<field>.
struct ProbeConfig {
  std::string name;
  double x = 0, y = 0;              ///< m
  std::vector<std::string> fields;  ///< of kProbeFields
};

/// What a probe can record: the field name and its unit.
struct ProbeField {
  const char* name;
  const char* unit;
};
inline constexpr ProbeField kProbeFields[] = {{"p", "Pa"},     {"rho", "kg/m^3"}, {"u", "m/s"},
                                              {"v", "m/s"},    {"T", "K"},        {"mach", "1"},
                                              {"alpha_p", "1"}};

struct OutputConfig {
  double interval = 0.0;  ///< s of simulated time between VTK outputs; 0: initial + final only
  bool vtk = true;        ///< write gas.pvd / parcels.pvd
  double surface_threshold = 1e-4;       ///< alpha_p of the dust surface (paper section 3.2)
  std::vector<double> surface_stations;  ///< m, x of the h(t) stations
  std::vector<BandConfig> bands;         ///< force-history bands (default: the paper's two)
  double band_bin_width = 1e-6;          ///< s, bins of t - t_arrival
  double band_duration = 0.0;            ///< s, last bin end (default: run end time)
  double contact_window = 1e-5;          ///< s, contact-force averaging window (paper: 0.01 ms)
  double shock_threshold = 0.05;         ///< relative pressure rise marking the shock
  /// s of simulated time between checkpoints (OUTDIR/checkpoint.h5); default: output.interval;
  /// 0: none by simulated time.
  double checkpoint_interval = 0.0;
  /// s of wall time after which the next step writes a checkpoint (so a long run never loses
  /// more than this); 0: none by wall time. A checkpoint is also written at the end and on
  /// SIGINT/SIGTERM.
  double checkpoint_wall_interval = 300.0;
  std::vector<ProbeConfig> probes;
  double probe_interval = 0.0;  ///< s of simulated time between probe samples; 0: every step
  bool parcel_fronts = false;   ///< series parcel_fronts (a curtain's fronts) at each output
  /// The fronts as a line of sight through the channel sees them (parcel_fronts.hpp).
  struct LineOfSight {
    double depth = 0.0;          ///< m, path through the cloud (default: the channel height)
    double optical_depth = 1.0;  ///< the edge: where n (pi d^2 / 4) depth falls below this
    double bin = 0.0;            ///< m, streamwise bins (default: the smallest cell width)
  } line_of_sight;
  // The dust cloud (series dust_cloud, dust_concentration_histogram, dust_entrainment;
  // docs/output.md), at each output of a scene with particles.
  bool dust_cloud = true;
  /// m: a parcel counts as lifted when its centre is higher than this above the layer
  /// rectangle's top; default: one particle diameter (the mass median of a distribution).
  double cloud_lift_height = 0.0;
  /// kg/m^3: the cloud's top is the highest flow-grid cell row above the layer where the
  /// concentration still reaches this.
  double cloud_top_concentration = 1e-3;
  /// m: side of the square cells of the filtered dust concentration; default: one parcel
  /// alone in a cell is a tenth of explosible_lower (at most the channel's height above the
  /// layer). Derived by dust_cloud_filter_width().
  double cloud_filter_width = 0.0;
  /// kg/m^3: the explosible band of the filtered concentration. 0.05: inside the 0.03-0.06
  /// kg/m^3 minimum explosible concentrations of coal, starch and grain dusts (Eckhoff 2003,
  /// Dust Explosions in the Process Industries, ch. 1); 2: the low end of the upper limits of
  /// a few kg/m^3 reported for such dusts (same source).
  double explosible_lower = 0.05;
  double explosible_upper = 2.0;
  /// m: particles smaller than this are the fines (75 um: the No. 200 sieve that defines float
  /// coal dust, US 30 CFR 75.400-1).
  double fines_diameter = 75e-6;
  /// m above the layer top: the heights of the vertical dust mass fluxes.
  std::vector<double> entrainment_heights;
  /// m: the stretches of channel of series dust_entrainment; default a fortieth of the layer.
  double entrainment_bin_width = 0.0;
};

/// ParaView Catalyst in situ (docs/catalyst.md): Python pipelines run on the live state.
struct CatalystConfig {
  bool enabled = false;              ///< the scene has an [insitu.catalyst] section
  std::vector<std::string> scripts;  ///< absolute paths of the Catalyst Python scripts (v1 or v2)
  long long interval_steps = 1;      ///< deliver every this many steps (interval = 0)
  double interval = 0.0;             ///< s of simulated time between deliveries; 0: by steps
  bool live = false;                 ///< also a pipeline that connects to ParaView Live
  std::string live_url = "localhost:22222";
};

struct InsituConfig {
  CatalystConfig catalyst;
};

struct GridConfig {
  AxisSpec x, y;
};

struct Scene {
  std::string source_file;
  RunConfig run;
  GridConfig grid;
  GasConfig gas;
  InitialCondition initial;
  DemConfig particles;
  CouplingConfig coupling;  ///< used when particles are enabled
  OutputConfig output;
  InsituConfig insitu;
  std::string resolved_toml;  ///< the whole scene with every default filled in
  /// The text and --set overrides it was parsed from: a checkpoint stores them so that a
  /// restart re-parses exactly the same scene (docs/reliability.md).
  std::string source_text;
  std::vector<std::string> overrides;
};

/// Reads, overrides (`key.path=value`, TOML value syntax; bare words are strings) and
/// validates a scene. Throws SceneError naming file, line and key on any problem.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

/// What the parser did with each key of the scene at `path` (declared, read, its default or
/// what the default is derived from, its range): the scene-key reference's facts
/// (solver/scene/scene_keys.hpp). Throws SceneError as load_scene does.
std::map<std::string, KeyFact> read_scene_keys(const std::string& path);

/// Same, from TOML text (`name` stands in for the file in messages).
Scene parse_scene(const std::string& text, const std::string& name,
                  const std::vector<std::string>& overrides = {});

}  // namespace dustlift
