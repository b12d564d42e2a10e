#pragma once
// A run on several MPI ranks (docs/parallel.md): each rank steps an x-slab of the grid and
// the parcels whose cells lie in it. The driver holds what only such a run has: the slab
// layout and its halo, the parcels' split, rank 0's gathered copy of the whole state for
// the observers and checkpoints, and the moves of the cuts that follow the work. The
// physics (GasSolver, ParcelSystem, GasParticleCoupling) runs as on one rank.
#include <memory>
#include <string>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/core/communicator.hpp"
#include "solver/parallel/parcel_slabs.hpp"
#include "solver/parallel/slab_decomposition.hpp"
#include "solver/parallel/slab_halo.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

class Simulation;

class SlabDriver {
 public:
  /// Cuts the whole grid of `sim` into balanced slabs (cells per column) and makes this
  /// rank's gas (Simulation's grid and gas become the slab's).
  SlabDriver(Simulation& sim, const Communicator& comm);
  ~SlabDriver();

  const Communicator& comm() const { return *comm_; }
  const SlabLayout& layout() const { return layout_; }
  SlabHalo& halo() { return *halo_; }

  /// Splits the parcels of the simulation over the ranks at the slab cuts (they must be the
  /// whole layer on every rank), with copies as far as a deposit square reaches.
  void split_parcels();
  /// Splits a one-rank system (a restored checkpoint's) at the slab cuts.
  void split(ParcelSystem& parcels) { parcel_slabs_->split(parcels, parcel_cuts()); }

  /// Collective: rank 0's copies of the whole gas, alpha_p and parcels take every rank's part
  /// of what `reads` says (Observer::StepRead bits); everything, the parcels with their
  /// contact history and the DEM's state, when `with_sources` (a checkpoint).
  void gather(bool with_sources, unsigned reads = Observer::kReadsEverything) const;
  /// Rank 0's gathered copies (null elsewhere and before a gather).
  const GasSolver* whole_gas() const { return whole_gas_.get(); }
  const ParcelSystem* whole_parcels() const { return whole_parcels_.get(); }
  const Field2D* whole_alpha_p() const { return whole_alpha_p_.get(); }
  int whole_rows_touched() const { return whole_rows_touched_; }

  /// Collective: moves the slab cuts to even out the work of the last step (cells each
  /// column updated, plus a share for the scans of resting cells, plus the parcels) when
  /// that lowers the largest slab's work by more than 5 %. The state moves exactly: results
  /// do not change. Returns whether the cuts moved.
  bool rebalance();
  long long rebalances() const { return rebalances_; }

  /// What a piece-writing observer sees of this rank (StateView::piece).
  const RunPiece& piece() const;

  /// This rank's cell-stage updates over all its slab solvers.
  long long cell_updates() const;
  /// The work summary's lines of a decomposed run (collective).
  std::string exchange_summary(long long steps) const;
  /// Per rank: the gas, halo and parcel-exchange seconds (collective; rank 0 formats them).
  std::string time_per_rank(double gas_seconds) const;
  double balance_seconds() const { return balance_seconds_; }

 private:
  void build_slab_gas();
  /// x of the slab cuts, where the parcels are split too.
  std::vector<double> parcel_cuts() const;
  /// with_lists: the contact history and the DEM's own state too (a checkpoint).
  /// band_only: only the parcels that started in an output band (Observer::step_reads).
  void gather_parcels(bool with_lists, bool band_only) const;

  Simulation& sim_;
  const Communicator* comm_;
  SlabLayout layout_;
  std::unique_ptr<SlabHalo> halo_;
  std::unique_ptr<ParcelSlabs> parcel_slabs_;
  mutable std::unique_ptr<GasSolver> whole_gas_;
  mutable std::unique_ptr<ParcelSystem> whole_parcels_;
  mutable std::unique_ptr<Field2D> whole_alpha_p_;
  mutable int whole_rows_touched_ = 0;
  mutable RunPiece piece_;
  long long rebalances_ = 0;
  long long retired_cell_updates_ = 0;  ///< by the slab solvers a rebalance replaced
  long long retired_halo_doubles_ = 0, retired_halo_messages_ = 0;
  double retired_halo_seconds_ = 0.0;
  double balance_seconds_ = 0.0;
};

}  // namespace dustlift
