// Which parcels a neighbour rebuild can give their last list again. In a resting bed most
// parcels have not moved since the last build; searching their 3x3 cells again would list the
// same partners in the same order, so their slots are copied instead and a rebuild's search
// costs what moved, not the whole bed.
#include <omp.h>

#include <algorithm>
#include <cmath>

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
  const DemDomain& d = cfg_.domain;
  changed_near_.assign(static_cast<std::size_t>(box_nx_) * static_cast<std::size_t>(box_ny_), 0);
  auto mark_around = [&](int cx, int cy) {
    for (int ry = std::max(cy - 1, 0); ry <= std::min(cy + 1, cells_y_ - 1); ++ry) {
      for (int ddx = -1; ddx <= 1; ++ddx) {
        int rx = cx + ddx;
        if (rx < 0 || rx >= cells_x_) {
          if (!d.periodic_x) continue;
          rx = rx < 0 ? rx + cells_x_ : rx - cells_x_;
        }
        if (in_box(rx, ry)) changed_near_[static_cast<std::size_t>(cell_index(rx, ry))] = 1;
      }
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (changed_parcels_[i] == 0) continue;
    const int c = cell_of_[i];
    mark_around(box_x0_ + (x_major_ ? c / box_ny_ : c % box_nx_),
                box_y0_ + (x_major_ ? c % box_ny_ : c / box_nx_));
    // Its cell at the last build, as the sort then computed it (the same cells since).
    const int cx = std::clamp(static_cast<int>(std::floor((x_build[i] - d.x_min) / cell_dx_)), 0,
                              cells_x_ - 1);
    const int cy = std::clamp(static_cast<int>(std::floor((y_build[i] - d.y_min) / cell_dy_)), 0,
                              cells_y_ - 1);
    if (!in_box(cx, cy)) return;  // a cell no longer stored: every parcel is searched
    mark_around(cx, cy);
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
