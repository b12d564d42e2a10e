#pragma once
// Drives a run: builds the models the scene enables, advances time (eq. 17 steps,
// landing exactly on output and end times) and notifies observers at output times.
// simulation.cpp sets up and steps, run_loop.cpp runs the schedule, run_report.cpp writes
// what the run did, snapshot.cpp saves and restores it; a run on several MPI ranks adds its
// SlabDriver (slab_driver.hpp).
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/core/communicator.hpp"
#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/parallel/slab_decomposition.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/derived_fields.hpp"
#include "solver/sim/observer.hpp"
#include "solver/sim/schedule.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

/// One progress report (for the CLI's progress line).
struct Progress {
  double time = 0.0, end_time = 0.0, dt = 0.0;
  long long step = 0;
  double wall_seconds = 0.0, eta_seconds = 0.0;
};

/// How run() ended.
enum class RunEnd {
  Completed,    ///< reached run.end_time
  StepLimit,    ///< stopped after run.max_steps
  Interrupted,  ///< the stop request said so (SIGINT/SIGTERM): checkpointed, no final frame
};

class SlabDriver;

class Simulation {
 public:
  /// With a communicator of several ranks the grid is cut into x-slabs, one per rank
  /// (docs/parallel.md): every rank must then make the same calls (advance, run, snapshot,
  /// restore, work_summary are collective). Observers belong on rank 0 and see the whole
  /// state gathered there, except those that write pieces (Observer::writes_pieces), which
  /// every rank adds in the same order and which see their rank's slab.
  explicit Simulation(const Scene& scene, const Communicator* comm = nullptr);
  ~Simulation();

  void add_observer(std::unique_ptr<Observer> observer);
  /// What the observers record about how the run was made (StateView::provenance).
  void set_provenance(Provenance provenance) { provenance_ = std::move(provenance); }
  void set_progress_callback(std::function<void(const Progress&)> callback);
  /// Where observers write log lines (StateView::log), e.g. a Catalyst script's traceback.
  void set_log(std::function<void(const std::string&)> log) { log_ = std::move(log); }

  /// Runs to the scene's end time (or max_steps, or a stop request). Throws NumericalFailure
  /// on a blow-up, naming step, time, cell and variable.
  ///
  /// Time targets: a step that would pass the next output time k * output.interval or the
  /// end time is shortened to end exactly on it (the time is set to the target, not summed
  /// up to it), so a run restarted from any checkpoint, or extended from its final one,
  /// takes the same steps as the run that was never interrupted (an extension: when its
  /// earlier end time was an output time). Observers that keep checkpoints
  /// (Observer::keeps_checkpoints, e.g. CheckpointKeeper) are asked after every step and
  /// get one after the last step and after the step during which a stop was requested.
  RunEnd run(const std::string& output_dir);

  /// Polled after every step (and its outputs); true stops the run as RunEnd::Interrupted.
  void set_stop_request(std::function<bool()> stop_requested);

  /// Everything the next step reads (gas, parcels with contact history, DEM internals,
  /// coupling carry-over, time, step and output counters, scene text) and the observers'
  /// state (insitu/<key>/: series so far, filter sums, file numbering). See snapshot.hpp.
  /// Collective in a decomposed run (rank 0's holds the state).
  Snapshot snapshot() const;
  /// Restores a snapshot taken from a simulation of the same scene (the caller builds this
  /// one from the scene text the snapshot carries), with the same observers added first.
  /// Throws SnapshotError if it does not fit. The run then continues bitwise as the one the
  /// snapshot was taken from, and run() resumes the observers' series (Observer::on_resume)
  /// instead of starting them; `previous_output_dir` is the folder they were written to.
  void restore(const Snapshot& s, const std::string& previous_output_dir = {});
  /// Index of the next output time (next_output * output.interval).
  long long next_output() const { return outputs_.next_index(); }

  /// Advances one step of at most `dt_max` (used by run() and by tests).
  double advance(double dt_max);

  /// What observers see: on rank 0 of a decomposed run the whole grid as last gathered.
  StateView view(const std::string& output_dir = {}) const;
  /// What an observer that writes pieces sees in a decomposed run: this rank's slab and its
  /// parcels (StateView::piece); the same as view() otherwise.
  StateView piece_view(const std::string& output_dir = {}) const;
  double time() const { return time_; }
  long long step() const { return step_; }
  const Scene& scene() const { return scene_; }
  GasSolver& gas() { return *gas_; }
  const GasSolver& gas() const { return *gas_; }
  /// This rank's grid: the whole grid, or its x-slab in a decomposed run.
  const Grid2D& grid() const { return grid_; }
  const Grid2D& whole_grid() const { return whole_grid_; }
  bool decomposed() const { return slabs_ != nullptr; }
  /// This rank's slab (one slab of the whole grid when not decomposed).
  const SlabLayout& slab() const;
  /// Rank 0 of a decomposed run: the gathered copy of the whole gas (null elsewhere, and
  /// when not decomposed).
  const GasSolver* whole_gas() const;
  /// The settled bed as made (describe_bed of the whole layer, before any split over ranks);
  /// empty unless the layer settles.
  const std::string& bed_description() const { return bed_description_; }
  /// Null in a gas-only scene.
  ParcelSystem* parcels() { return parcels_.get(); }
  const ParcelSystem* parcels() const { return parcels_.get(); }
  const GasParticleCoupling* coupling() const { return coupling_.get(); }
  GasParticleCoupling* coupling() { return coupling_.get(); }
  /// The gas's configuration (what a new slab's gas is made with).
  const GasConfig& gas_config() const { return gas_config_; }
  /// A run on several ranks: makes this rank's grid the columns [first_column, end_column) of
  /// the whole grid and a new, uninitialised gas on it (the split, and every move of the
  /// cuts). Returns the cell updates the replaced gas had made (0 when there was none).
  long long replace_slab(int first_column, int end_column);

  /// What the run computed (gas cell-stage updates against the full grid, DEM sub-steps and
  /// neighbour rebuilds) and where the wall time went, for the log.
  std::string work_summary() const;
  /// Wall seconds of run() by phase (the coupling's and the DEM's from their own timers).
  struct Timings {
    double gas = 0.0, observers = 0.0, checkpoints = 0.0;
    double balance = 0.0;  ///< moving slab cuts (a decomposed run)
  };
  /// Collective in a decomposed run: moves the slab cuts to follow the work
  /// (SlabDriver::rebalance). advance() calls it every run.rebalance_steps steps.
  bool rebalance();
  long long rebalances() const;
  const Timings& timings() const { return timings_; }

  /// The physical effects this scene switches on, one short phrase each (for `dustlift info`).
  std::vector<std::string> enabled_effects() const;

 private:
  bool any_rank(bool value) const;
  /// kg/m^3 of the real particles (0 in a gas-only scene): the dust concentration's factor.
  double particle_density() const {
    return scene_.particles.enabled ? scene_.particles.density : 0.0;
  }
  /// restore()'s steps: the parcels, the DEM's internals and the coupling's carried state
  /// (checked on a copy, then swapped in); the gas fields read before (conserved, sources,
  /// porosity, primitives) into this rank's grid.
  void restore_parcels(const Snapshot& s, std::size_t cells);
  void assign_gas(const std::array<const std::vector<double>*, 14>& gas_fields);
  /// run()'s steps. What a decomposed run gathers on rank 0 for the observers of the whole
  /// state (gather: at all; output_reads: Observer::StepRead bits at outputs, rank 0's).
  struct GatherPlan {
    bool gather = false;
    unsigned output_reads = 0;
  };
  /// The previous progress report's simulated time and wall seconds (eta.hpp).
  struct EtaMark {
    double time = 0.0, wall = 0.0;
  };
  void count_from_here();  ///< the work counters at the start of run(), for work_summary()
  GatherPlan plan_gathers() const;
  void start_observers(const std::string& output_dir, const GatherPlan& plan);
  /// After a step: the gather its readers need, on_step, and on_output when one is due.
  void observe_step(const std::string& output_dir, const GatherPlan& plan, bool output_due);
  bool checkpoints_due(const RunClock& now);  ///< any keeper's, on any rank
  void report_progress(const RunClock& now, double end, double dt, EtaMark& eta);
  /// Builds the snapshot (collectively) and hands it to the checkpoint keepers.
  void make_checkpoint(const RunClock& now);
  /// The view an observer's calls get: its piece on several ranks when it writes pieces.
  StateView view_for(const Observer& o, const StateView& whole, const StateView& piece) const {
    return decomposed() && o.writes_pieces() ? piece : whole;
  }

  Scene scene_;
  Grid2D whole_grid_;
  Grid2D grid_;
  GasConfig gas_config_;
  SlabLayout one_slab_;  ///< slab() of a run on one rank
  std::unique_ptr<GasSolver> gas_;
  std::unique_ptr<SlabDriver> slabs_;              ///< only on several ranks
  std::unique_ptr<ParcelSystem> parcels_;          ///< only when the scene has particles
  std::unique_ptr<GasParticleCoupling> coupling_;  ///< only when the scene has particles
  std::size_t total_parcels_ = 0;                  ///< parcels in the whole run (every rank's own)
  std::string bed_description_;
  std::vector<std::unique_ptr<Observer>> observers_;
  /// Derived fields of what view() and piece_view() show, made at most once per step.
  mutable DerivedFields derived_whole_, derived_piece_;
  std::function<void(const Progress&)> progress_;
  std::function<void(const std::string&)> log_;
  std::function<bool()> stop_requested_;
  Provenance provenance_;
  bool restored_ = false;     ///< run() resumes the observers instead of starting them
  std::string resumed_from_;  ///< folder the restored run wrote to
  double time_ = 0.0;
  long long step_ = 0;
  Cadence outputs_;  ///< output.interval (its next index is carried in checkpoints)
  Timings timings_;
  // Counters at the start of run(), for work_summary().
  long long first_step_ = 0, first_cell_updates_ = 0, first_dem_steps_ = 0, first_rebuilds_ = 0,
            first_kept_lists_ = 0;
  long long first_parcel_substeps_ = 0;
};

/// Ghost layers the gas scheme needs (MUSCL: 2).
inline constexpr int kGhostLayers = 2;
/// Fewest columns of an MPI rank's slab: its ghost columns must be its neighbours' interior
/// cells, and its two edges' ghost-width strips (the edge activity of the skipping) must not
/// overlap.
inline constexpr int kMinSlabColumns = 2 * kGhostLayers;

}  // namespace dustlift
