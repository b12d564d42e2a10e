#pragma once
// Observers read the simulation at output times through a read-only StateView.
// insitu/ implements them (VTK writers, filters, series); the solver never
// includes insitu/ headers, VTK or HDF5.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "solver/core/grid.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/schedule.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

class ParcelSystem;         // solver/dem/parcel_system.hpp
class GasParticleCoupling;  // solver/coupling/gas_particle_coupling.hpp
class Communicator;         // solver/core/communicator.hpp
class DerivedFields;        // solver/sim/derived_fields.hpp

/// How the run was made, for the files that record it (VTK field data, series.h5 attributes).
struct Provenance {
  std::string code_version;  ///< "0.1.0 (git a240b3b)"
  std::string command_line;  ///< the dustlift command that started this run (segment)
};

/// The part of a decomposed run one rank holds, for the observers that write one piece per
/// rank (Observer::writes_pieces): the view's grid, gas and alpha_p are then the rank's slab,
/// whose interior columns are the whole grid's columns [column_bounds[rank],
/// column_bounds[rank + 1]), and its parcels the rank's table, in which the copies of other
/// ranks' parcels are flagged.
struct RunPiece {
  const Communicator* comm = nullptr;  ///< every rank of the run (collective writes)
  int rank = 0;
  std::vector<int> column_bounds;  ///< per rank, as SlabLayout::bounds
  int whole_columns() const { return column_bounds.back(); }
  /// The slab's ghost columns at its cuts hold the neighbours' current cells (one each side
  /// where the slab has a neighbour): derivatives at a cut read them, as one rank would.
  bool neighbour_left() const { return rank > 0; }
  bool neighbour_right() const { return rank + 2 < static_cast<int>(column_bounds.size()); }
  /// Per parcel of the view's table: 1 = another rank's copy (a ghost), not written here.
  /// Empty: every parcel is the rank's own.
  std::span<const std::uint8_t> parcel_copies;
};

struct StateView {
  const Scene* scene = nullptr;
  const Grid2D* grid = nullptr;
  const GasSolver* gas = nullptr;
  GasPrimitives primitives{};
  const ParcelSystem* parcels = nullptr;          ///< null in a gas-only scene
  const GasParticleCoupling* coupling = nullptr;  ///< null in a gas-only scene
  /// Particle volume fraction as deposited (eq. 12, before the porosity cap); null in a
  /// gas-only scene. Use it rather than 1 - alpha_g, which one-way coupling leaves at 0.
  const Field2D* alpha_p = nullptr;
  double time = 0.0;  ///< s
  long long step = 0;
  std::string output_dir;                  ///< the run's output folder
  const Provenance* provenance = nullptr;  ///< null: not recorded
  /// The run's log (run.log and the terminal), one line per call; null: no log (tests).
  const std::function<void(const std::string&)>* log = nullptr;
  /// Set for an observer that writes pieces, in a decomposed run: the rank's slab (RunPiece).
  /// Null: the view shows the whole run (one rank, or the state gathered on rank 0).
  const RunPiece* piece = nullptr;
  /// Fields derived from what the view shows (the vorticity), made at most once per step
  /// whoever asks first. Views made by hand (tests) may leave it null.
  const DerivedFields* derived = nullptr;
};

class Observer {
 public:
  virtual ~Observer() = default;
  /// Called once before the first step (time 0 state).
  virtual void on_start(const StateView& view) { on_output(view); }
  /// Called at each output time of the scene's cadence.
  virtual void on_output(const StateView& view) = 0;
  /// Called after every step; keep it cheap (filters that need every step use it).
  virtual void on_step(const StateView&) {}
  /// Whether on_step will read the state at this step (view.time and view.step are current,
  /// the fields may not be): a decomposed run gathers the whole grid on rank 0 only for a
  /// step some observer reads. An observer that overrides on_step must say when it reads.
  virtual bool reads_step(const StateView&) const { return false; }
  /// What on_step reads at a step it reads (StepRead bits): a decomposed run gathers on
  /// rank 0 only that (filters that sample every step would otherwise gather the whole grid
  /// and parcel table every step). Default: everything.
  enum StepRead : unsigned {
    kReadsPressure = 1u,     ///< the gas pressure
    kReadsAlphaP = 2u,       ///< the deposited alpha_p
    kReadsGas = 4u,          ///< every gas field
    kReadsBandParcels = 8u,  ///< the parcels that started in the scene's output bands
    kReadsParcels = 16u,     ///< every parcel
    kReadsEverything = 31u
  };
  virtual unsigned step_reads() const { return kReadsEverything; }
  /// What on_start, on_output and on_finish read (StepRead bits): a decomposed run gathers
  /// on rank 0 at outputs only what its observers of the whole state read. Default:
  /// everything.
  virtual unsigned output_reads() const { return kReadsEverything; }
  /// Whether this observer writes one piece per rank in a decomposed run: it is then made on
  /// every rank, called on every rank at the same points with its slab's view
  /// (StateView::piece; its calls may be collective), and needs no gather. Otherwise it
  /// lives on rank 0 and sees the whole state gathered there.
  virtual bool writes_pieces() const { return false; }
  /// Called once after the last step of a run that reached its end (or step limit); not
  /// after an interruption (the next segment continues the same series).
  virtual void on_finish(const StateView& view) { on_output(view); }

  // ---- Continuing a run from a checkpoint (docs/reliability.md) ----
  /// Name of this observer's state in a checkpoint (datasets under insitu/<key>/); empty for
  /// an observer without state worth carrying.
  virtual std::string state_key() const { return {}; }
  /// Adds the state a continued run needs (series so far, filter sums, file numbering) to
  /// `snapshot`, every name starting with `prefix` ("insitu/<key>/").
  virtual void save_state(Snapshot&, const std::string& /*prefix*/) const {}
  /// Takes that state back; throws SnapshotError naming the array when it does not fit.
  virtual void restore_state(const Snapshot&, const std::string& /*prefix*/) {}
  /// Called instead of on_start when the run continues a restored state: no new frame (the
  /// restored time was written before the checkpoint, if it was an output time); the files
  /// are brought back to the checkpoint's state. `previous_output_dir` is the folder the
  /// restored run wrote to (the checkpoint's folder), which may differ from view.output_dir.
  virtual void on_resume(const StateView&, const std::string& /*previous_output_dir*/) {}

  // ---- Keeping the run's checkpoints ----
  /// Whether this observer keeps checkpoints. It is then made on every rank (writes_pieces)
  /// and asked after every step but the last whether one is due (on any rank: one rank's
  /// wall clock may say so); when one is, every rank helps build the snapshot (whole on
  /// rank 0) and hands it to on_checkpoint. One is also made after the last step of a run,
  /// an interrupted one included, unless that step's is made already.
  virtual bool keeps_checkpoints() const { return false; }
  /// Called after every step but the last (now.wall: seconds since the run segment began);
  /// a cadence in simulated time moves on here whether or not a checkpoint is made.
  virtual bool checkpoint_due(const RunClock& /*now*/) { return false; }
  virtual void on_checkpoint(const Snapshot&, const RunClock& /*now*/) {}
};

}  // namespace dustlift
