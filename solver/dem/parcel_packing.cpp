// Moving whole parcels between tables: packing a parcel with its contact history, appending
// packed parcels, reordering the rows, and assembling a one-rank system from the packed
// parcels of every rank (checkpoints, observers, a move of the slab cuts). No MPI here: the
// messages are solver/parallel/'s.
#include <algorithm>
#include <array>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "solver/dem/parcel_ranks.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {

std::size_t ParcelSystem::owned_count() const {
  if (rank_copy.empty()) return size();
  return static_cast<std::size_t>(std::count(rank_copy.begin(), rank_copy.end(), std::uint8_t{0}));
}

void ParcelSystem::pack_parcel(std::size_t i, bool with_history, std::vector<double>& out) const {
  pack_row(i, out);
  const bool listed = with_history && nbr_offset.size() == size() + 1;
  const std::int32_t k0 = listed ? nbr_offset[i] : 0, k1 = listed ? nbr_offset[i + 1] : 0;
  out.push_back(static_cast<double>(k1 - k0));
  for (std::int32_t k = k0; k < k1; ++k) {
    out.push_back(
        static_cast<double>(id[static_cast<std::size_t>(nbr_index[static_cast<std::size_t>(k)])]));
    out.push_back(nbr_delta[static_cast<std::size_t>(k)]);
  }
}

const double* ParcelSystem::append_packed(const double* row, bool ghost) {
  row = append_packed_row(row, ghost);
  const auto count = static_cast<std::int32_t>(*row++);
  for (std::int32_t k = 0; k < count; ++k) {
    hist_partner_.push_back(static_cast<std::int32_t>(*row++));
    hist_delta_.push_back(*row++);
  }
  hist_offset_.push_back(hist_offset_.back() + count);
  return row;
}

void ParcelSystem::reorder_parcels(const std::vector<std::int32_t>& source) {
  // The lists, skins and flags of the last build no longer match the rows: none kept next.
  near_fast_before_.clear();
  // Before the first rebuild the rebuilt columns are empty: give them the table's rows.
  const std::size_t rows = size();
  half_skin.resize(rows);
  wall_mask.resize(rows);
  permute_rows(source, true, true);
  const std::size_t n = source.size();
  // The carried history (CSR over the rows) follows its rows.
  std::vector<std::int32_t> offset(n + 1, 0), partner;
  std::vector<double> delta;
  for (std::size_t k = 0; k < n; ++k) {
    const auto s = static_cast<std::size_t>(source[k]);
    for (std::int32_t q = hist_offset_[s]; q < hist_offset_[s + 1]; ++q) {
      partner.push_back(hist_partner_[static_cast<std::size_t>(q)]);
      delta.push_back(hist_delta_[static_cast<std::size_t>(q)]);
    }
    offset[k + 1] = static_cast<std::int32_t>(partner.size());
  }
  hist_offset_.swap(offset);
  hist_partner_.swap(partner);
  hist_delta_.swap(delta);
}

void ParcelSystem::clear_carried_history() {
  hist_offset_.assign(size() + 1, 0);
  hist_partner_.clear();
  hist_delta_.clear();
}

void ParcelSystem::carry_listed_history() {
  const std::size_t n = size();
  hist_offset_.assign(n + 1, 0);
  hist_partner_.clear();
  hist_delta_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_rank_copy(i)) {
      for (std::int32_t k = nbr_offset[i]; k < nbr_offset[i + 1]; ++k) {
        hist_partner_.push_back(
            id[static_cast<std::size_t>(nbr_index[static_cast<std::size_t>(k)])]);
        hist_delta_.push_back(nbr_delta[static_cast<std::size_t>(k)]);
      }
    }
    hist_offset_[i + 1] = static_cast<std::int32_t>(hist_partner_.size());
  }
}

std::vector<std::int32_t> ParcelSystem::sort_table_by_key() {
  std::vector<std::int32_t> by_key(size());
  std::iota(by_key.begin(), by_key.end(), 0);
  std::sort(by_key.begin(), by_key.end(), [&](std::int32_t a, std::int32_t b) {
    return order_key[static_cast<std::size_t>(a)] < order_key[static_cast<std::size_t>(b)];
  });
  reorder_parcels(by_key);
  return by_key;
}

void ParcelSystem::pack_owned(std::vector<double>& out, bool with_history,
                              const std::function<bool(std::size_t)>& keep) const {
  for (std::size_t i = 0; i < size(); ++i) {
    if (!is_rank_copy(i) && (!keep || keep(i))) pack_parcel(i, with_history, out);
  }
}

void ParcelSystem::assign_packed(const std::vector<std::vector<double>>& pieces) {
  // Start from an empty table with this system's columns.
  const std::vector<std::int32_t> none;
  order_key.resize(size());
  rank_copy.assign(size(), 0);
  x_build.resize(size());
  y_build.resize(size());
  clear_carried_history();
  reorder_parcels(none);
  half_skin.clear();
  wall_mask.clear();
  for (const auto& piece : pieces) {
    const double* row = piece.data();
    const double* end = piece.data() + piece.size();
    while (row < end) row = append_packed(row, false);
  }
  const std::size_t n = size();
  const std::vector<std::int32_t> by_key = sort_table_by_key();
  // The history becomes the neighbour list, partners by index.
  std::unordered_map<std::int32_t, std::int32_t> index_of;
  for (std::size_t i = 0; i < n; ++i) index_of[id[i]] = static_cast<std::int32_t>(i);
  nbr_offset = hist_offset_;
  nbr_index.resize(hist_partner_.size());
  for (std::size_t k = 0; k < hist_partner_.size(); ++k) {
    const auto it = index_of.find(hist_partner_[k]);
    if (it == index_of.end())
      throw std::invalid_argument("ParcelSystem::assign_packed: a partner is missing");
    nbr_index[k] = it->second;
  }
  nbr_image.assign(hist_partner_.size(), 0);
  nbr_delta = hist_delta_;
  inv_skin2.resize(half_skin.size());
  for (std::size_t i = 0; i < half_skin.size(); ++i) {
    inv_skin2[i] = half_skin[i] > 0.0 ? 1.0 / (half_skin[i] * half_skin[i]) : 0.0;
  }
  order_key.clear();
  rank_copy.clear();
  counts_known_ = false;
}

void ParcelSystem::decompose(ParcelRanks& ranks) {
  ranks_ = &ranks;
  counts_known_ = false;  // every rank decides the contact pass again, together
}

void ParcelSystem::drop_decomposition() {
  ranks_ = nullptr;
  order_key.clear();
  rank_copy.clear();
  counts_known_ = false;
}

void ParcelSystem::refresh_rank_copies(std::span<const ParcelColumn> columns) {
  if (ranks_ == nullptr) return;
  std::array<std::vector<double>*, 8> arrays{};
  if (columns.size() > arrays.size()) {
    throw std::invalid_argument("ParcelSystem::refresh_rank_copies: at most 8 columns at once");
  }
  for (std::size_t k = 0; k < columns.size(); ++k) arrays[k] = &column(columns[k]);
  ranks_->refresh_copies(*this, std::span(arrays.data(), columns.size()));
}

}  // namespace dustlift
