#pragma once
// What the DEM asks of a split of its parcels over ranks. solver/parallel/parcel_slabs.hpp
// implements it on x-slabs over a Communicator; a one-rank system has none and speaks no MPI.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dustlift {

class ParcelSystem;

class ParcelRanks {
 public:
  virtual ~ParcelRanks() = default;
  /// Reductions over the ranks, so that every rank takes the same decisions (the cell size,
  /// the sub-step count, the skins, whether to rebuild).
  virtual double min(double value) const = 0;
  double max(double value) const { return -min(-value); }
  virtual bool any(bool value) const = 0;
  /// Before a rebuild's sort: the parcels go to their owners with their contact history,
  /// fresh copies of the others' parcels come in, and the table takes the one-rank order;
  /// the history is left as the rebuild's carried history. Returns whether there was a list
  /// before (on every rank alike).
  virtual bool redistribute(ParcelSystem& parcels) = 0;
  /// After the rebuild's cell sort (`old_index[new] = old`; `permuted`: the rows moved).
  virtual void after_sort(ParcelSystem& parcels, const std::vector<std::int32_t>& old_index,
                          bool permuted) = 0;
  /// The owners' values of these per-parcel arrays to their copies (one message per
  /// neighbour).
  virtual void refresh_copies(ParcelSystem& parcels,
                              std::span<std::vector<double>* const> columns) = 0;
};

}  // namespace dustlift
