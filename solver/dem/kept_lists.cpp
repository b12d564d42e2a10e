// Which parcels a neighbour rebuild can give their last list again. In a resting bed most
// parcels have not moved since the last build; searching their 3x3 cells again would list the
// same partners in the same order, so their slots are copied instead and a rebuild's search
// costs what moved, not the whole bed.
#include <omp.h>

#include "solver/dem/parcel_system.hpp"

namespace dustlift {

void ParcelSystem::mark_kept_lists(bool possible, double s_base) {
  const std::size_t n = size();
  keeps_list_.clear();
  near_fast_.resize(n);
  // The last build's list, skins and positions, in the current parcel order (no re-sort since).
  possible = possible && skin_before_.size() == n && near_fast_before_.size() == n &&
             x_build.size() == n && y_build.size() == n && old_offset_.size() == n + 1;
  changed_parcels_.resize(n);
  std::size_t changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    const bool fast = half_skin[i] > s_base;
    const bool fast_partner = extra_start_[i + 1] > extra_start_[i];
    near_fast_[i] = (fast || fast_partner) ? 1 : 0;
    if (possible) {
      const bool moved =
          x[i] != x_build[i] || y[i] != y_build[i] || half_skin[i] != skin_before_[i];
      changed_parcels_[i] = moved ? 1 : 0;
      changed += moved ? 1 : 0;
    }
  }
  // With most of the bed moving, few lists could be kept and marking around every moved
  // parcel (one thread) would cost more than it saves: search them all.
  if (!possible || 2 * changed > n) return;

  // A parcel's search reads the positions and skins of the parcels in its 3x3 cells, and
  // which parcels those are. Unmoved parcels stay in their cells, so those cells hold the same
  // parcels in the same order unless one that changed is in one of them now or was at the
  // last build: the cells within one of such a cell are marked.
  changed_near_.assign(static_cast<std::size_t>(box_nx_) * static_cast<std::size_t>(box_ny_), 0);
  auto mark_around = [&](int c) {
    for_each_cell_near(c, 1, [&](int rx, int ry, int) {
      changed_near_[static_cast<std::size_t>(cell_index(rx, ry))] = 1;
    });
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (changed_parcels_[i] == 0) continue;
    mark_around(cell_of_[i]);
    // Its cell at the last build, as the sort then computed it (the same cells since).
    const int cx = cell_column(x_build[i]), cy = cell_row(y_build[i]);
    if (!in_box(cx, cy)) return;  // a cell no longer stored: every parcel is searched
    mark_around(cell_index(cx, cy));
  }
  keeps_list_.resize(n);
  long long kept = 0;
#pragma omp parallel for schedule(static) reduction(+ : kept) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    // Fast parcels and their partners have slots from wider searches: always searched.
    const bool keep = changed_parcels_[i] == 0 && near_fast_[i] == 0 && near_fast_before_[i] == 0 &&
                      changed_near_[static_cast<std::size_t>(cell_of_[i])] == 0;
    keeps_list_[i] = keep ? 1 : 0;
    kept += keep ? 1 : 0;
  }
  kept_lists_ += kept;
  // list_partners writes the new list into nbr_*; the kept slots are read from the old one.
  nbr_index.swap(old_nbr_index_);
  nbr_image.swap(old_nbr_image_);
}

}  // namespace dustlift
