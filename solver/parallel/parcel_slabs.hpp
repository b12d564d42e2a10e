#pragma once
// The parcels of a ParcelSystem split over x-slabs of MPI ranks: each rank keeps the parcels
// whose neighbour-cell column lies between the cuts (x of the boundaries between ranks 0|1,
// 1|2, ...; a cut is rounded to the nearest cell face) and copies of the others' parcels
// within contact reach of its columns (plus a margin) and of every listed partner of its
// own. The results are bitwise those of one rank: every loop runs in the one-rank parcel
// order, the rebuild, sort and sub-step decisions are collective, and the copies' states
// are refreshed every sub-step. Parcels change owner at rebuilds, with their contact
// history. Not for periodic x.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "solver/core/communicator.hpp"
#include "solver/dem/parcel_ranks.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {

class ParcelSlabs final : public ParcelRanks {
 public:
  /// `comm` must outlive this; this must outlive the systems it splits.
  explicit ParcelSlabs(const Communicator& comm);

  /// Splits `parcels` over the ranks at `cuts`. Every rank must hold the same table when this
  /// is called (each builds the same layer, or reads the same checkpoint); a system between
  /// two rebuilds keeps its lists. One system at a time: splitting another (after
  /// ParcelSystem::drop_decomposition of the first) starts the exchange lists anew.
  void split(ParcelSystem& parcels, std::vector<double> cuts);
  /// New cuts, applied at the next rebuild (the parcels move then).
  void set_cuts(std::vector<double> cuts);
  /// Copies also within this distance (m) beyond the contact reach, from the next rebuild:
  /// what the coupling's stencils need around a cut.
  void set_copy_margin(double margin) { copy_margin_ = margin; }

  /// Exchange counters: parcels sent to another owner (and of them, those touching another
  /// parcel or a wall with a tangential elongation to carry), copies sent at rebuilds,
  /// doubles and messages sent, and the seconds spent in them.
  struct Counters {
    long long migrated = 0, migrated_with_history = 0, copies_sent = 0, doubles_sent = 0,
              messages = 0;
    double seconds = 0.0;
  };
  const Counters& counters() const { return counters_; }

  // ParcelRanks
  double min(double value) const override;
  bool any(bool value) const override;
  bool redistribute(ParcelSystem& parcels) override;
  void after_sort(ParcelSystem& parcels, const std::vector<std::int32_t>& old_index,
                  bool permuted) override;
  void refresh_copies(ParcelSystem& parcels,
                      std::span<std::vector<double>* const> columns) override;

 private:
  /// split's split of a table every rank holds alike.
  void split_replicated(ParcelSystem& ps);
  /// split_replicated's needs: [q][i] is 1 where rank q holds parcel i (its own, a copy
  /// within reach of its columns, or a listed partner of its own).
  std::vector<std::vector<std::uint8_t>> held_by_rank(const ParcelSystem& ps,
                                                      const std::vector<int>& owner,
                                                      int reach) const;
  /// split_replicated's exchange lists (new_index: a parcel's row here, -1 if not held).
  void list_replicated_copies(const std::vector<int>& owner,
                              const std::vector<std::vector<std::uint8_t>>& needed,
                              const std::vector<std::int32_t>& new_index);
  /// The neighbour lists of the kept rows: own parcels keep theirs (partners renumbered),
  /// copies have none.
  void keep_own_lists(ParcelSystem& ps, const std::vector<int>& owner,
                      const std::vector<std::int32_t>& keep,
                      const std::vector<std::int32_t>& new_index) const;
  /// Each row's owner, by its cell column.
  std::vector<int> owners(const ParcelSystem& ps) const;
  /// Whether cell column cx lies within `reach` columns of rank q's.
  bool near_rank(int cx, int q, int reach) const;
  /// redistribute's steps: the own parcels that leave, packed for their new owners (with the
  /// history when there was a list); the own parcels within reach of another rank's columns,
  /// packed as copies; the messages with their sizes; the parcels received, appended.
  void pack_leaving(const ParcelSystem& ps, const std::vector<int>& owner, bool had_list);
  void pack_copies(const ParcelSystem& ps, int reach);
  void exchange_sized();
  void take_in(ParcelSystem& ps, bool copies);
  /// Each rank's first cell column (first_column_) from the cuts.
  void update_first_columns(const ParcelSystem& ps);
  /// Collective: how many cell columns beyond a rank's own its copies reach.
  int copy_reach_columns(const ParcelSystem& ps) const;
  /// The exchange lists after a reorder (old_of_new[k]: the old index of row k).
  void follow_rows(const std::vector<std::int32_t>& old_of_new);
  int owner_of_column(int cx) const;

  const Communicator* comm_;
  std::vector<double> cuts_;
  std::vector<int> first_column_;  ///< of each rank's cell columns, plus the end
  double copy_margin_ = 0.0;       ///< m, copies beyond the contact reach
  std::vector<std::vector<std::int32_t>> send_copies_;  ///< per rank: own parcels it copies
  std::vector<std::vector<std::int32_t>> recv_copies_;  ///< per rank: its copies here, same order
  std::vector<std::vector<double>> send_buf_, recv_buf_;
  Counters counters_;
};

}  // namespace dustlift
