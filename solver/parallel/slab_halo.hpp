#pragma once
// A slab's neighbouring ranks: the ghost columns a slab shares with its neighbours, all fields
// of one exchange in one message per direction. It fills the gas solver's cut sides
// (GhostFiller) and the coupling's fields (GasHalo).
#include <span>
#include <string>
#include <vector>

#include "solver/core/communicator.hpp"
#include "solver/coupling/gas_halo.hpp"
#include "solver/gas/ghost_filler.hpp"
#include "solver/parallel/slab_decomposition.hpp"

namespace dustlift {

class GasSolver;

class SlabHalo final : public GasHalo, public GhostFiller {
 public:
  SlabHalo(const Communicator& comm, SlabLayout layout, const Grid2D& slab_grid);

  /// Makes `gas` (on this slab's grid) one slab of the whole: its ghosts at the cuts filled
  /// from the neighbours, its fault checks and its skipping within run.rest_tolerance agreed
  /// over the ranks, naming cells by their column in the whole grid. Before gas.initialize();
  /// this halo must outlive `gas`'s steps.
  void attach(GasSolver& gas);

  bool owns_left_boundary() const override { return layout_.owns_left_boundary(); }
  bool owns_right_boundary() const override { return layout_.owns_right_boundary(); }
  void exchange_columns(std::span<Field2D* const> fields) override;

  bool collective() const override { return true; }
  /// The primitives' ghost columns at the cuts; with the gas solver's updated ranges, which
  /// rows it updated next to each cut go along (changed_beyond).
  void fill(const PrimitiveGhosts& ghosts) override;
  void fill_porosity(Field2D& alpha) override;
  bool changed_beyond(GridSide side, int j0, int j1) const override;

  /// Doubles and messages this rank has sent (for the scaling model of docs/parallel.md).
  long long doubles_sent() const { return doubles_sent_; }
  long long messages_sent() const { return messages_sent_; }
  /// Wall seconds spent in exchange_columns (the transfer and any wait for a slower neighbour).
  double seconds() const { return seconds_; }

 private:
  /// Marks in edge_updates_ the edge columns of each row that the updated ranges reach.
  void mark_edge_updates(const int* lo, const int* hi);

  const Communicator& comm_;
  SlabLayout layout_;
  int nx_ = 0, ny_ = 0, rows_ = 0, ng_ = 0, stride_ = 0;
  /// 1 in a row's edge columns where the gas solver's last stage updated cells there, 0
  /// elsewhere; exchanged with the primitives, its ghost columns then say where the
  /// neighbour's last stage updated the cells that this slab's stencils read.
  Field2D edge_updates_;
  std::vector<double> send_, receive_;
  long long doubles_sent_ = 0, messages_sent_ = 0;
  double seconds_ = 0.0;
};

}  // namespace dustlift
