// Cell sort and Verlet neighbour list of the ParcelSystem.
// Parcels are re-sorted by cell (stable counting sort) at every rebuild, so neighbours
// are close in memory; the list keeps every parcel within r_i + r_j + skin, and is
// rebuilt when some parcel has moved more than skin/2 since the last build. The
// tangential history of each pair is carried over by matching partner ids.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "solver/dem/parcel_system.hpp"
#include "solver/dem/permute.hpp"

namespace dustlift {

void ParcelSystem::update_cell_geometry() {
  const std::size_t n = size();
  const DemDomain& d = cfg_.domain;
  // Cells at least as wide as the largest cutoff so that all candidates lie in the 3x3 block.
  double d_max = 0.0;
  const double* dia = diameter.data();
#pragma omp parallel for schedule(static) reduction(max : d_max) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) d_max = std::max(d_max, dia[i]);
  if (ranks_ != nullptr) d_max = ranks_->max(d_max);  // the same cells on every rank
  // The contact units' reach beyond touching (e.g. the cohesion's cut-off; 0 without one)
  // widens every reach by as much.
  const double cutoff = d_max + skin_ + pair_reach_;
  radius_max_ = 0.5 * d_max;
  cutoff_ = cutoff;
  cells_x_ = std::max(1, static_cast<int>(std::floor(length_x_ / cutoff)));
  cells_y_ = std::max(1, static_cast<int>(std::floor((d.y_max - d.y_min) / cutoff)));
  if (d.periodic_x && cells_x_ < 3) {
    throw std::invalid_argument("ParcelSystem: periodic x needs a domain at least 3 cutoffs long");
  }
  // Number the cells along the short axis first: a parcel's neighbours then lie within a
  // few dozen places of it in memory (the paper's layer is 3,600 cells long, 18 high).
  x_major_ = cells_x_ >= cells_y_;
  cell_dx_ = length_x_ / cells_x_;
  cell_dy_ = (d.y_max - d.y_min) / cells_y_;
}

void ParcelSystem::sort_by_cell(bool permute_data) {
  const std::size_t n = size();
  const DemDomain& d = cfg_.domain;

  if (d.periodic_x) {
    // Wrap into [x_min, x_max): positions stay unwrapped between rebuilds (images are fixed).
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
    for (std::size_t i = 0; i < n; ++i) {
      const double shift = std::floor((x[i] - d.x_min) / length_x_) * length_x_;
      x[i] -= shift;
      if (x[i] >= d.x_max) x[i] -= length_x_;  // round-off at the edge
    }
  }
  // The cells are stored only over the box the parcels occupy (the paper's channel has
  // millions of cells above and beside the layer, and every rebuild walked them three times);
  // the numbering keeps the domain's (cx, cy) order, so the sort and the lists are the same.
  cell_of_.resize(n);
  cell_y_.resize(n);
  int cx_lo = cells_x_, cx_hi = 0, cy_lo = cells_y_, cy_hi = 0;
  // clang-format off
#pragma omp parallel for schedule(static) reduction(min : cx_lo, cy_lo) reduction(max : cx_hi, cy_hi) if (n >= kParallelMinimum)
  // clang-format on
  for (std::size_t i = 0; i < n; ++i) {
    const int cx = cell_column(x[i]), cy = cell_row(y[i]);
    cell_of_[i] = cx;
    cell_y_[i] = cy;
    cx_lo = std::min(cx_lo, cx);
    cx_hi = std::max(cx_hi, cx);
    cy_lo = std::min(cy_lo, cy);
    cy_hi = std::max(cy_hi, cy);
  }
  box_x0_ = n > 0 ? cx_lo : 0;
  box_y0_ = n > 0 ? cy_lo : 0;
  box_nx_ = n > 0 ? cx_hi - cx_lo + 1 : 1;
  box_ny_ = n > 0 ? cy_hi - cy_lo + 1 : 1;
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) cell_of_[i] = cell_index(cell_of_[i], cell_y_[i]);
  const std::size_t n_cells = static_cast<std::size_t>(box_nx_) * static_cast<std::size_t>(box_ny_);
  cell_start_.assign(n_cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
  for (std::size_t c = 0; c < n_cells; ++c) cell_start_[c + 1] += cell_start_[c];
  order_.resize(n);
  cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);  // fill cursors
  for (std::size_t i = 0; i < n; ++i) order_[cursor_[cell_of_[i]]++] = static_cast<std::int32_t>(i);

  if (!permute_data) {
    // The parcels keep their places (they moved less than their skins since the last sort,
    // so memory order is still close to cell order); the cells list them by index instead.
    members_.swap(order_);
    old_index_.resize(n);
#pragma omp parallel for simd schedule(static) if (n >= kParallelMinimum)
    for (std::size_t i = 0; i < n; ++i) old_index_[i] = static_cast<std::int32_t>(i);
    return;
  }
  ++data_permutations_;
  // The carried columns (and the ranks' order keys and copy flags); the rebuilt ones are
  // made after this sort.
  permute_rows(order_, true, false);
  permute(cell_of_, order_, scratch_i_);
  old_index_.swap(order_);
  members_.resize(n);
#pragma omp parallel for simd schedule(static) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) members_[i] = static_cast<std::int32_t>(i);
}

ParcelSystem::SkinLimits ParcelSystem::skin_limits() const {
  SkinLimits l;
  l.base = 0.5 * skin_;
  l.time = cfg_.fast_skin_substeps * stable_time_step();
  // Fast skins stay within a block of cells that the periodic images cannot wrap around.
  int max_block = 8;
  if (cfg_.domain.periodic_x) max_block = std::min(max_block, (cells_x_ - 1) / 2);
  l.cap = std::max(l.base, max_block * std::min(cell_dx_, cell_dy_) - cutoff_);
  return l;
}

double ParcelSystem::listing_reach() const {
  // Every pair a rebuild can list has a gap below the two skins: 2 r_max + 2 s_max, with
  // s_max the largest skin any parcel may get now or still move by (the last rebuild's).
  const SkinLimits limits = skin_limits();
  double speed_max = 0.0, skin_max = limits.base;
  const bool built = half_skin.size() == size();
  for (std::size_t i = 0; i < size(); ++i) {
    if (is_rank_copy(i)) continue;
    speed_max = std::max(speed_max, std::sqrt(vx[i] * vx[i] + vy[i] * vy[i]));
    if (built) skin_max = std::max(skin_max, half_skin[i]);
  }
  const double s = std::max(skin_max, std::clamp(speed_max * limits.time, limits.base, limits.cap));
  const double s_max = ranks_ != nullptr ? ranks_->max(s) : s;
  return 2.0 * radius_max_ + 2.0 * s_max + pair_reach_;
}

void ParcelSystem::rebuild_neighbours() {
  counts_known_ = false;  // parcels may have moved between ranks
  update_cell_geometry();
  // A decomposed run first moves parcels to their owners and renews the rank copies; the history
  // travels with the parcels (redistribute leaves it carried by the rows).
  const bool distributed = ranks_ != nullptr;
  const bool had_list = distributed ? ranks_->redistribute(*this) : nbr_offset.size() == size() + 1;
  if (distributed) {
    old_offset_ = hist_offset_;
    old_partner_id_ = hist_partner_;
    old_delta_ = hist_delta_;
  } else if (had_list) {
    key_history_by_partner_id();
  }
  // The data are re-sorted by cell every kSortEvery rebuilds (and at the first): moving 40
  // columns costs more than the list itself, and memory order decays slowly.
  constexpr long long kSortEvery = 8;
  const bool permuted = !had_list || rebuilds_ % kSortEvery == 0;
  sort_by_cell(permuted);  // old_index_[new] = old
  if (distributed) ranks_->after_sort(*this, old_index_, permuted);
  const SkinLimits limits = skin_limits();
  skin_before_.assign(half_skin.begin(), half_skin.end());
  const double s_max = assign_skins(limits);
  list_fast_pairs(s_max);
  index_fast_pairs(limits.base);
  const ListingGeometry geometry{cells_x_, cells_y_, cell_dx_, cell_dy_, pair_reach_};
  mark_kept_lists(keep_unchanged_lists_ && !distributed && had_list && !permuted &&
                      geometry == listed_geometry_,
                  limits.base);
  list_partners(limits.base, had_list);
  listed_geometry_ = geometry;
  near_fast_before_.swap(near_fast_);
  mask_walls();
  mark_build_positions(distributed);
  needs_rebuild_ = false;
  ++rebuilds_;
}

void ParcelSystem::key_history_by_partner_id() {
  // Ids survive the re-sort; indices do not.
  const std::size_t n = size();
  old_offset_.swap(nbr_offset);
  old_delta_.swap(nbr_delta);
  const std::size_t slots = nbr_index.size();
  old_partner_id_.resize(slots);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < slots; ++k) old_partner_id_[k] = id[nbr_index[k]];
}

double ParcelSystem::assign_skins(const SkinLimits& limits) {
  // Per-parcel skin (the distance a parcel may move before the list is rebuilt): the base
  // skin/2 for most parcels, more for the fast ones so that one parcel blown through the gas
  // does not make every parcel's list be rebuilt every few sub-steps. A pair is listed when
  // its gap is below s_i + s_j, so no contact can be missed before one of them has moved
  // its own skin (integrate() then asks for a rebuild).
  const std::size_t n = size();
  const double s_base = limits.base, s_time = limits.time, s_cap = limits.cap;
  half_skin.resize(n);
  double s_max = s_base;
#pragma omp parallel for schedule(static) reduction(max : s_max) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    const double speed = std::sqrt(vx[i] * vx[i] + vy[i] * vy[i]);
    const double s = std::clamp(speed * s_time, s_base, s_cap);
    half_skin[i] = s;
    s_max = std::max(s_max, s);
  }
  if (ranks_ != nullptr) s_max = ranks_->max(s_max);
  fast_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (half_skin[i] > s_base) fast_.push_back(static_cast<std::int32_t>(i));
  }
  return s_max;
}

template <class F>
void ParcelSystem::for_each_nearby(std::size_t i, int block, F&& f) const {
  for_each_cell_near(cell_of_[i], block, [&](int rx, int ry, int image) {
    const int cell = cell_index(rx, ry);
    for (std::int32_t q = cell_start_[cell]; q < cell_start_[cell + 1]; ++q) {
      const std::int32_t j = members_[static_cast<std::size_t>(q)];
      if (static_cast<std::size_t>(j) != i) f(j, image);
    }
  });
}

bool ParcelSystem::within_listing_reach(std::size_t i, std::int32_t j, int image) const {
  const double ddx = x[j] + image * length_x_ - x[i], ddy = y[j] - y[i];
  const double reach = radius[i] + radius[j] + half_skin[i] + half_skin[j] + pair_reach_;
  return ddx * ddx + ddy * ddy < reach * reach;
}

void ParcelSystem::list_fast_pairs(double s_max) {
  // Fast parcels search a block wide enough for any partner; the pairs they find are listed
  // on both sides (a slow partner would not find them in its 3x3 block).
  const double min_cell = std::min(cell_dx_, cell_dy_);
  const std::size_t n_fast = fast_.size();
  // In parallel over contiguous ranges of fast parcels, joined in order (thread-independent;
  // every range is searched however many threads come).
  const int threads = n_fast >= 64 ? omp_get_max_threads() : 1;
  fast_pairs_by_thread_.resize(static_cast<std::size_t>(threads));
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (threads > 1)
  for (int t = 0; t < threads; ++t) {
    std::vector<FastPair>& mine = fast_pairs_by_thread_[static_cast<std::size_t>(t)];
    mine.clear();
    const std::size_t f0 = n_fast * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
    const std::size_t f1 =
        n_fast * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads);
    for (std::size_t f = f0; f < f1; ++f) {
      const auto i = static_cast<std::size_t>(fast_[f]);
      const double r = 2.0 * radius_max_ + half_skin[i] + s_max + pair_reach_;
      const int block = std::max(1, static_cast<int>(std::ceil(r / min_cell)));
      for_each_nearby(i, block, [&](std::int32_t j, int image) {
        if (within_listing_reach(i, j, image))
          mine.push_back({static_cast<std::int32_t>(i), j, static_cast<std::int8_t>(image)});
      });
    }
  }
  fast_pairs_.clear();
  for (const auto& part : fast_pairs_by_thread_)
    fast_pairs_.insert(fast_pairs_.end(), part.begin(), part.end());
}

void ParcelSystem::index_fast_pairs(double s_base) {
  // Slow partners of fast parcels, sorted by (slow parcel, fast parcel): their extra slots.
  const std::size_t n = size();
  extra_pairs_.clear();
  for (const FastPair& fp : fast_pairs_) {
    if (half_skin[static_cast<std::size_t>(fp.j)] <= s_base) {
      extra_pairs_.push_back({fp.j, fp.i, static_cast<std::int8_t>(-fp.image)});
    }
  }
  std::sort(extra_pairs_.begin(), extra_pairs_.end(), [](const FastPair& a, const FastPair& b) {
    return a.i != b.i ? a.i < b.i : a.j < b.j;
  });
  extra_start_.assign(n + 1, 0);
  for (const FastPair& e : extra_pairs_) ++extra_start_[static_cast<std::size_t>(e.i) + 1];
  for (std::size_t i = 0; i < n; ++i) extra_start_[i + 1] += extra_start_[i];
  fast_start_.assign(n + 1, 0);
  for (const FastPair& fp : fast_pairs_) ++fast_start_[static_cast<std::size_t>(fp.i) + 1];
  for (std::size_t i = 0; i < n; ++i) fast_start_[i + 1] += fast_start_[i];
}

template <class F>
void ParcelSystem::for_each_partner(std::size_t i, double s_base, F&& f) const {
  // Fast parcels: the pairs they found. Slow parcels: slow partners from the 3x3 block, then
  // the fast ones that found them.
  if (half_skin[i] > s_base) {
    for (std::int32_t k = fast_start_[i]; k < fast_start_[i + 1]; ++k) {
      const FastPair& fp = fast_pairs_[static_cast<std::size_t>(k)];
      f(fp.j, fp.image);
    }
    return;
  }
  for_each_nearby(i, 1, [&](std::int32_t j, int image) {
    if (half_skin[static_cast<std::size_t>(j)] <= s_base && within_listing_reach(i, j, image))
      f(j, image);
  });
  for (std::int32_t k = extra_start_[i]; k < extra_start_[i + 1]; ++k) {
    const FastPair& e = extra_pairs_[static_cast<std::size_t>(k)];
    f(e.j, e.image);
  }
}

namespace {

/// Range t of `ranges` contiguous ranges over n parcels: [i0, i1).
void parcel_range(std::size_t n, int t, int ranges, std::size_t& i0, std::size_t& i1) {
  i0 = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(ranges);
  i1 = n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(ranges);
}

}  // namespace

void ParcelSystem::list_partners(double s_base, bool had_list) {
  // One search per parcel: the parcels are cut into one contiguous range per thread, each
  // range lists its partners into its own buffer, then the buffers are joined in parcel
  // order (the same list whatever the thread count) and the history of pairs listed before
  // is carried over.
  const std::size_t n = size();
  nbr_offset.resize(n + 1);
  nbr_offset[0] = 0;
  const int ranges = n >= kParallelMinimum ? std::max(1, omp_get_max_threads()) : 1;
  list_by_range_.resize(static_cast<std::size_t>(ranges));
  // Over the ranges, not the threads: every range is listed however many threads come.
#pragma omp parallel for schedule(static, 1) num_threads(ranges) if (ranges > 1)
  for (int t = 0; t < ranges; ++t) list_range(t, ranges, s_base);
  for (std::size_t i = 0; i < n; ++i) nbr_offset[i + 1] += nbr_offset[i];
  const std::size_t slots = static_cast<std::size_t>(nbr_offset[n]);
  nbr_index.resize(slots);
  nbr_image.resize(slots);
  nbr_delta.resize(slots);
#pragma omp parallel for schedule(static, 1) num_threads(ranges) if (ranges > 1)
  for (int t = 0; t < ranges; ++t) fill_range(t, ranges, had_list);
}

void ParcelSystem::list_range(int t, int ranges, double s_base) {
  std::size_t i0 = 0, i1 = 0;
  parcel_range(size(), t, ranges, i0, i1);
  std::vector<ListedPartner>& mine = list_by_range_[static_cast<std::size_t>(t)];
  mine.clear();
  const bool keeping = !keeps_list_.empty();
  for (std::size_t i = i0; i < i1; ++i) {
    const std::size_t before = mine.size();
    if (keeping && keeps_list_[i] != 0) {
      // The same partners in the same order as the search would give (mark_kept_lists).
      for (std::int32_t s = old_offset_[i]; s < old_offset_[i + 1]; ++s)
        mine.push_back({old_nbr_index_[static_cast<std::size_t>(s)],
                        old_nbr_image_[static_cast<std::size_t>(s)]});
    } else {
      for_each_partner(i, s_base, [&](std::int32_t j, int image) {
        mine.push_back({j, static_cast<std::int8_t>(image)});
      });
    }
    nbr_offset[i + 1] = static_cast<std::int32_t>(mine.size() - before);
  }
}

void ParcelSystem::fill_range(int t, int ranges, bool had_list) {
  std::size_t i0 = 0, i1 = 0;
  parcel_range(size(), t, ranges, i0, i1);
  const std::vector<ListedPartner>& mine = list_by_range_[static_cast<std::size_t>(t)];
  const auto first = static_cast<std::size_t>(nbr_offset[i0]);
  for (std::size_t k = 0; k < mine.size(); ++k) {
    nbr_index[first + k] = mine[k].j;
    nbr_image[first + k] = mine[k].image;
    nbr_delta[first + k] = 0.0;
  }
  if (!had_list) return;
  for (std::size_t i = i0; i < i1; ++i) {
    // Carry over the history of pairs that were listed before.
    const std::int32_t o = old_index_[i];
    for (std::int32_t s = nbr_offset[i]; s < nbr_offset[i + 1]; ++s) {
      const std::int32_t pid = id[nbr_index[s]];
      for (std::int32_t q = old_offset_[o]; q < old_offset_[o + 1]; ++q) {
        if (old_partner_id_[q] == pid) {
          nbr_delta[s] = old_delta_[q];
          break;
        }
      }
    }
  }
}

void ParcelSystem::mask_walls() {
  // Walls each parcel may touch before the next rebuild (it moves less than its skin until
  // then, and less than a skin per step, so a wall contact also gets its end seen).
  const std::size_t n = size();
  const DemDomain& d = cfg_.domain;
  wall_mask.resize(n);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    const double reach = radius[i] + 2.0 * half_skin[i] + wall_reach_;
    std::uint8_t mask = 0;
    if (d.wall_bottom && y[i] - d.y_min < reach) mask |= 1u << static_cast<int>(Wall::Bottom);
    if (d.wall_top && d.y_max - y[i] < reach) mask |= 1u << static_cast<int>(Wall::Top);
    if (d.wall_left && x[i] - d.x_min < reach) mask |= 1u << static_cast<int>(Wall::Left);
    if (d.wall_right && d.x_max - x[i] < reach) mask |= 1u << static_cast<int>(Wall::Right);
    // A wall history left from before (e.g. restored from a checkpoint) is seen as well.
    for (int w = 0; w < kWallCount; ++w) {
      if (wall_delta[i * kWallCount + w] != 0.0) mask |= 1u << w;
    }
    wall_mask[i] = mask;
  }
}

void ParcelSystem::mark_build_positions(bool distributed) {
  // The positions of this build and the skins' inverse squares, in parallel (no allocation:
  // same sizes as before).
  const std::size_t n = size();
  x_build.resize(n);
  y_build.resize(n);
  inv_skin2.resize(n);
#pragma omp parallel for simd schedule(static) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    x_build[i] = x[i];
    y_build[i] = y[i];
    inv_skin2[i] = 1.0 / (half_skin[i] * half_skin[i]);
  }
  // A rank copy's moves are its owner's to judge: it never asks for a rebuild here.
  if (distributed) {
    for (std::size_t i = 0; i < n; ++i) {
      if (rank_copy[i] != 0) inv_skin2[i] = 0.0;
    }
  }
}

}  // namespace dustlift
