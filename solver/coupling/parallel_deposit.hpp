#pragma once
// Deposits of parcels into grid cells (eqs. 12-15) in parallel, with exactly the sums a
// serial pass in parcel order gives (so results do not depend on the thread count):
// the parcels are split into contiguous chunks, one per thread (they are sorted along x by
// the DEM, so each chunk covers a band of grid columns); a column that two chunks' stencils
// reach is "shared". Phase A: every chunk adds, in parcel order, all its contributions to
// cells outside the shared columns (each such cell hears from one chunk only). Phase B: the
// contributions to the shared columns, serially in parcel order. Each cell's sum is then
// added up in parcel order, as in the serial pass. Entries outside columns [0, nx) are
// skipped: on an MPI rank's slab they are the neighbour's cells, which it sums itself.
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "solver/coupling/grid_transfer.hpp"

namespace dustlift {

class ParallelDeposit {
 public:
  /// Plans the chunks for the first `count` of these stencils (parcel order) on a grid of
  /// nx columns: run() then visits those parcels only.
  void plan(const std::vector<DepositStencil>& stencils, std::size_t count, int nx, std::size_t parallel_minimum) {
    const std::size_t n = std::min(count, stencils.size());
    const int threads = n >= parallel_minimum ? std::max(1, omp_get_max_threads()) : 1;
    chunk_start_.resize(static_cast<std::size_t>(threads) + 1);
    for (int c = 0; c <= threads; ++c) {
      chunk_start_[static_cast<std::size_t>(c)] = n * static_cast<std::size_t>(c) / static_cast<std::size_t>(threads);
    }
    // Columns each chunk reaches; a column reached by two chunks is shared.
    reach_count_.assign(static_cast<std::size_t>(nx), 0);
    lo_.assign(static_cast<std::size_t>(threads), nx);
    hi_.assign(static_cast<std::size_t>(threads), -1);
    bool outside = false;  // a stencil entry outside [0, nx): a slab's, on the neighbour's side
#pragma omp parallel for schedule(static, 1) num_threads(threads) reduction(|| : outside) if (threads > 1)
    for (int c = 0; c < threads; ++c) {
      int lo = nx, hi = -1;
      for (std::size_t k = chunk_start_[static_cast<std::size_t>(c)]; k < chunk_start_[static_cast<std::size_t>(c) + 1]; ++k) {
        const DepositStencil& d = stencils[k];
        for (int m = 0; m < d.count; ++m) {
          const int i = d.i[static_cast<std::size_t>(m)];
          if (i < 0 || i >= nx) {
            outside = true;
            continue;
          }
          lo = std::min(lo, i);
          hi = std::max(hi, i);
        }
      }
      lo_[static_cast<std::size_t>(c)] = lo;
      hi_[static_cast<std::size_t>(c)] = hi;
    }
    for (int c = 0; c < threads; ++c) {
      for (int i = lo_[static_cast<std::size_t>(c)]; i <= hi_[static_cast<std::size_t>(c)]; ++i) {
        ++reach_count_[static_cast<std::size_t>(i)];
      }
    }
    threads_ = threads;
    nx_ = nx;
    // One rank's stencils all lie in [0, nx): run() then skips the test per entry.
    all_inside_ = !outside;
    // The parcels that reach a shared column, in parcel order (chunk by chunk).
    // One list per thread the run may use, each reserved once for a chunk's share of all the
    // stencils: a growing active region (skipping within a tolerance) then never reallocates
    // them, not even when it grows past parallel_minimum. Unused lists stay empty.
    const std::size_t slots = static_cast<std::size_t>(std::max(threads, omp_get_max_threads()));
    if (deferred_by_chunk_.size() < slots) deferred_by_chunk_.resize(slots);
    const std::size_t most = (stencils.size() + slots - 1) / slots;
    for (std::vector<std::size_t>& list : deferred_by_chunk_) {
      if (list.capacity() < most) list.reserve(most);
      list.clear();
    }
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (threads > 1)
    for (int c = 0; c < threads; ++c) {
      std::vector<std::size_t>& list = deferred_by_chunk_[static_cast<std::size_t>(c)];
      if (threads == 1) continue;
      for (std::size_t k = chunk_start_[static_cast<std::size_t>(c)]; k < chunk_start_[static_cast<std::size_t>(c) + 1]; ++k) {
        const DepositStencil& d = stencils[k];
        bool reaches = false;
        for (int m = 0; m < d.count; ++m) reaches = reaches || shared(d.i[static_cast<std::size_t>(m)]);
        if (reaches) list.push_back(k);
      }
    }
  }

  bool inside(int i) const { return i >= 0 && i < nx_; }
  bool shared(int i) const { return inside(i) && reach_count_[static_cast<std::size_t>(i)] > 1; }

  /// Calls add(k, m) for every stencil entry m of every parcel k, in the two phases above.
  template <class Add>
  void run(const std::vector<DepositStencil>& stencils, Add&& add) const {
    // Phase A without the tests it does not need (the same calls in the same order): one
    // chunk shares no column; one rank's stencils all lie inside.
    if (threads_ == 1 && all_inside_) {
      phase_a<false, false>(0, stencils, add);
      return;
    }
#pragma omp parallel for schedule(static, 1) num_threads(threads_) if (threads_ > 1)
    for (int c = 0; c < threads_; ++c) {
      if (all_inside_) {
        phase_a<false, true>(c, stencils, add);
      } else {
        phase_a<true, true>(c, stencils, add);
      }
    }
    if (threads_ == 1) return;
    // Phase B: the shared columns' contributions, in parcel order (the chunks are in order).
    for (const std::vector<std::size_t>& list : deferred_by_chunk_) {
      for (std::size_t k : list) {
        const DepositStencil& d = stencils[k];
        for (int m = 0; m < d.count; ++m) {
          if (shared(d.i[static_cast<std::size_t>(m)])) add(k, m);
        }
      }
    }
  }

 private:
  /// Phase A of chunk c: every entry outside the shared columns (and inside [0, nx)).
  template <bool CheckInside, bool CheckShared, class Add>
  void phase_a(int c, const std::vector<DepositStencil>& stencils, Add& add) const {
    const int* reach = reach_count_.data();
    const int nx = nx_;
    for (std::size_t k = chunk_start_[static_cast<std::size_t>(c)]; k < chunk_start_[static_cast<std::size_t>(c) + 1]; ++k) {
      const DepositStencil& d = stencils[k];
      for (int m = 0; m < d.count; ++m) {
        const int i = d.i[static_cast<std::size_t>(m)];
        if constexpr (CheckInside) {
          if (i < 0 || i >= nx) continue;
        }
        if constexpr (CheckShared) {
          if (reach[i] > 1) continue;
        }
        add(k, m);
      }
    }
  }

  int threads_ = 1;
  int nx_ = 0;
  bool all_inside_ = true;
  std::vector<std::size_t> chunk_start_;
  std::vector<int> reach_count_, lo_, hi_;
  std::vector<std::vector<std::size_t>> deferred_by_chunk_;
};

}  // namespace dustlift
