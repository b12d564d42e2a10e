// The parcels on x-slabs of MPI ranks (issue 12, docs/parallel.md).
//
// Exactness: a decomposed run gives the one-rank run's bits. Each parcel carries its index
// in the one-rank parcel order (order_key); every rank keeps its table in that order, so the
// neighbour lists, the contact sums and the cell sort visit parcels as one rank would. The
// cuts lie on neighbour-cell faces, and cells are numbered along y first, so after a
// permuting sort rank r's parcels are the one-rank order's positions [offset_r, offset_r +
// count_r): the new keys need only the counts of the ranks before. Rebuilds, the sub-step
// count and the cell size are decided collectively. A ghost (a copy of another rank's
// parcel within contact reach) is never integrated as its own: its forces are skipped and
// its state is its owner's after every sub-step.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "solver/dem/parcel_system.hpp"
#include "solver/dem/permute.hpp"
#include "solver/parallel/communicator.hpp"

namespace dustlift {
namespace {

class SecondsSince {
 public:
  explicit SecondsSince(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~SecondsSince() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  SecondsSince(const SecondsSince&) = delete;
  SecondsSince& operator=(const SecondsSince&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

void ParcelSystem::set_decomposition(const Communicator& comm, std::vector<double> cuts) {
  if (cfg_.domain.periodic_x) {
    throw std::invalid_argument(
        "ParcelSystem: a periodic channel's parcels cannot be split over ranks");
  }
  if (comm_ != nullptr) throw std::logic_error("ParcelSystem::set_decomposition: already split");
  comm_ = &comm;
  set_cuts(std::move(cuts));
  const std::size_t n = size();
  order_key.resize(n);
  std::iota(order_key.begin(), order_key.end(), std::int64_t{0});
  rank_copy.assign(n, 0);
  const auto ranks = static_cast<std::size_t>(comm.size());
  send_ghosts_.assign(ranks, {});
  recv_ghosts_.assign(ranks, {});
  send_buf_.assign(ranks, {});
  recv_buf_.assign(ranks, {});
  split_replicated();
}

void ParcelSystem::update_first_columns() {
  if (!x_major_) {
    throw std::invalid_argument(
        "ParcelSystem: parcels split over ranks need a domain longer than high");
  }
  // Each rank's first cell column: the cuts rounded to the nearest cell face.
  const int ranks = comm_->size();
  first_column_.assign(static_cast<std::size_t>(ranks) + 1, 0);
  for (int q = 1; q < ranks; ++q) {
    const double c =
        std::round((cuts_[static_cast<std::size_t>(q - 1)] - cfg_.domain.x_min) / cell_dx_);
    first_column_[static_cast<std::size_t>(q)] =
        std::max(first_column_[static_cast<std::size_t>(q - 1)],
                 static_cast<int>(std::clamp(c, 0.0, double(cells_x_))));
  }
  first_column_[static_cast<std::size_t>(ranks)] = cells_x_;
}

int ParcelSystem::ghost_reach_columns() const {
  // Every pair a rebuild can list has a gap below the two skins: 2 r_max + 2 s_max, with
  // s_max the largest skin any parcel may get now or still move by (the last rebuild's).
  const SkinLimits limits = skin_limits();
  double speed_max = 0.0, skin_max = limits.base;
  const bool built = half_skin.size() == size();
  for (std::size_t i = 0; i < size(); ++i) {
    if (rank_copy[i] != 0) continue;
    speed_max = std::max(speed_max, std::sqrt(vx[i] * vx[i] + vy[i] * vy[i]));
    if (built) skin_max = std::max(skin_max, half_skin[i]);
  }
  const double s = std::max(skin_max, std::clamp(speed_max * limits.time, limits.base, limits.cap));
  const double s_max = -comm_->min(-s);
  return static_cast<int>(std::ceil((2.0 * radius_max_ + 2.0 * s_max + ghost_margin_) / cell_dx_)) +
         1;
}

void ParcelSystem::split_replicated() {
  // Every rank holds the same table: each keeps its own parcels, and as ghosts the others'
  // within reach of its columns and every listed partner of its own (a system split between
  // two rebuilds keeps its lists, so a restart continues bitwise).
  const SecondsSince timer(counters_.seconds);
  update_cell_geometry();
  update_first_columns();
  const int ranks = comm_->size(), me = comm_->rank();
  const std::size_t n = size();
  const int reach = ghost_reach_columns();
  std::vector<int> owner(n), column(n);
  for (std::size_t i = 0; i < n; ++i) {
    column[i] = cell_column(x[i]);
    owner[i] = owner_of_column(column[i]);
  }
  // needed[q][i]: rank q holds parcel i (as its own or as a ghost).
  std::vector<std::vector<std::uint8_t>> needed(static_cast<std::size_t>(ranks),
                                                std::vector<std::uint8_t>(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    for (int q = 0; q < ranks; ++q) {
      const bool near = column[i] >= first_column_[static_cast<std::size_t>(q)] - reach &&
                        column[i] < first_column_[static_cast<std::size_t>(q) + 1] + reach;
      if (owner[i] == q || near) needed[static_cast<std::size_t>(q)][i] = 1;
    }
  }
  const bool listed = nbr_offset.size() == n + 1;
  if (listed) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::int32_t k = nbr_offset[i]; k < nbr_offset[i + 1]; ++k) {
        needed[static_cast<std::size_t>(owner[i])]
              [static_cast<std::size_t>(nbr_index[static_cast<std::size_t>(k)])] = 1;
      }
    }
  }
  const std::vector<std::uint8_t>& mine = needed[static_cast<std::size_t>(me)];
  std::vector<std::int32_t> keep, new_index(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (mine[i] == 0) continue;
    new_index[i] = static_cast<std::int32_t>(keep.size());
    keep.push_back(static_cast<std::int32_t>(i));
  }
  // The exchange lists, in table order on both sides.
  for (std::size_t i = 0; i < n; ++i) {
    if (owner[i] == me) {
      for (int q = 0; q < ranks; ++q) {
        if (q != me && needed[static_cast<std::size_t>(q)][i] != 0) {
          send_ghosts_[static_cast<std::size_t>(q)].push_back(new_index[i]);
        }
      }
    } else if (mine[i] != 0) {
      recv_ghosts_[static_cast<std::size_t>(owner[i])].push_back(new_index[i]);
    }
  }
  // Own parcels keep their lists (partners renumbered); ghosts have none.
  if (listed) {
    std::vector<std::int32_t> offset(keep.size() + 1, 0), index;
    std::vector<std::int8_t> image;
    std::vector<double> delta;
    for (std::size_t k = 0; k < keep.size(); ++k) {
      const auto i = static_cast<std::size_t>(keep[k]);
      if (owner[i] == me) {
        for (std::int32_t s = nbr_offset[i]; s < nbr_offset[i + 1]; ++s) {
          const auto slot = static_cast<std::size_t>(s);
          index.push_back(new_index[static_cast<std::size_t>(nbr_index[slot])]);
          image.push_back(nbr_image[slot]);
          delta.push_back(nbr_delta[slot]);
        }
      }
      offset[k + 1] = static_cast<std::int32_t>(index.size());
    }
    nbr_offset.swap(offset);
    nbr_index.swap(index);
    nbr_image.swap(image);
    nbr_delta.swap(delta);
  }
  for (std::size_t i = 0; i < n; ++i) rank_copy[i] = owner[i] != me ? 1 : 0;
  hist_offset_.assign(n + 1, 0);
  hist_partner_.clear();
  hist_delta_.clear();
  reorder_parcels(keep);
  if (listed) {
    // Between rebuilds a ghost never asks for one (as after a rebuild).
    inv_skin2.resize(size());
    for (std::size_t i = 0; i < size(); ++i) {
      inv_skin2[i] = rank_copy[i] != 0 ? 0.0 : 1.0 / (half_skin[i] * half_skin[i]);
    }
  }
}

void ParcelSystem::drop_decomposition() {
  comm_ = nullptr;
  cuts_.clear();
  first_column_.clear();
  order_key.clear();
  rank_copy.clear();
  send_ghosts_.clear();
  recv_ghosts_.clear();
}

void ParcelSystem::set_cuts(std::vector<double> cuts) {
  if (comm_ == nullptr || cuts.size() + 1 != static_cast<std::size_t>(comm_->size())) {
    throw std::invalid_argument("ParcelSystem::set_cuts: one cut between each two ranks");
  }
  for (std::size_t k = 1; k < cuts.size(); ++k) {
    if (!(cuts[k] >= cuts[k - 1]))
      throw std::invalid_argument("ParcelSystem::set_cuts: cuts must ascend");
  }
  cuts_ = std::move(cuts);
}

std::size_t ParcelSystem::owned_count() const {
  if (rank_copy.empty()) return size();
  return static_cast<std::size_t>(std::count(rank_copy.begin(), rank_copy.end(), std::uint8_t{0}));
}

int ParcelSystem::cell_column(double px) const {
  // The cell sort's own expression (neighbour_list.cpp), so that owner and cell agree.
  return std::clamp(static_cast<int>(std::floor((px - cfg_.domain.x_min) / cell_dx_)), 0,
                    cells_x_ - 1);
}

int ParcelSystem::owner_of_column(int cx) const {
  const auto it = std::upper_bound(first_column_.begin(), first_column_.end(), cx);
  return std::clamp(static_cast<int>(it - first_column_.begin()) - 1, 0, comm_->size() - 1);
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

std::vector<std::int32_t> ParcelSystem::sort_table_by_key() {
  std::vector<std::int32_t> by_key(size());
  std::iota(by_key.begin(), by_key.end(), 0);
  std::sort(by_key.begin(), by_key.end(), [&](std::int32_t a, std::int32_t b) {
    return order_key[static_cast<std::size_t>(a)] < order_key[static_cast<std::size_t>(b)];
  });
  reorder_parcels(by_key);
  return by_key;
}

void ParcelSystem::follow_rows(const std::vector<std::int32_t>& old_of_new) {
  std::vector<std::int32_t> new_of_old(old_of_new.size());
  for (std::size_t k = 0; k < old_of_new.size(); ++k) {
    new_of_old[static_cast<std::size_t>(old_of_new[k])] = static_cast<std::int32_t>(k);
  }
  for (auto* lists : {&send_ghosts_, &recv_ghosts_}) {
    for (auto& l : *lists) {
      for (std::int32_t& e : l) e = new_of_old[static_cast<std::size_t>(e)];
    }
  }
}

bool ParcelSystem::redistribute() {
  const SecondsSince timer(counters_.seconds);
  const Communicator& comm = *comm_;
  const int ranks = comm.size(), me = comm.rank();
  update_first_columns();

  const std::size_t n0 = size();
  const bool had_list = comm.any(nbr_offset.size() == n0 + 1);
  std::vector<int> owner(n0);
  for (std::size_t i = 0; i < n0; ++i) owner[i] = owner_of_column(cell_column(x[i]));

  // 1. Owned parcels leaving this rank, packed with their history (the list is still valid).
  for (auto& b : send_buf_) b.clear();
  for (std::size_t i = 0; i < n0; ++i) {
    if (rank_copy[i] != 0 || owner[i] == me) continue;
    pack_parcel(i, had_list, send_buf_[static_cast<std::size_t>(owner[i])]);
    ++counters_.migrated;
    bool elongated = false;
    for (int w = 0; w < kWallCount; ++w)
      elongated = elongated || wall_delta[i * kWallCount + static_cast<std::size_t>(w)] != 0.0;
    if (nbr_offset.size() == n0 + 1) {
      for (std::int32_t k = nbr_offset[i]; k < nbr_offset[i + 1]; ++k)
        elongated = elongated || nbr_delta[static_cast<std::size_t>(k)] != 0.0;
    }
    counters_.migrated_with_history += elongated ? 1 : 0;
  }
  // 2. The rows that stay (owned and still ours), with their history as partner ids.
  const int reach = ghost_reach_columns();
  auto near_rank = [&](int cx, int q) {
    return cx >= first_column_[static_cast<std::size_t>(q)] - reach &&
           cx < first_column_[static_cast<std::size_t>(q) + 1] + reach;
  };
  for (auto& l : send_ghosts_) l.clear();
  for (auto& l : recv_ghosts_) l.clear();
  std::vector<std::int32_t> keep;
  keep.reserve(n0);
  for (std::size_t i = 0; i < n0; ++i) {
    if (rank_copy[i] == 0 && owner[i] == me) keep.push_back(static_cast<std::int32_t>(i));
  }
  hist_offset_.assign(n0 + 1, 0);
  hist_partner_.clear();
  hist_delta_.clear();
  const bool listed_here = had_list && nbr_offset.size() == n0 + 1;
  for (std::size_t i = 0; i < n0; ++i) {
    if (listed_here && rank_copy[i] == 0) {
      for (std::int32_t k = nbr_offset[i]; k < nbr_offset[i + 1]; ++k) {
        hist_partner_.push_back(
            id[static_cast<std::size_t>(nbr_index[static_cast<std::size_t>(k)])]);
        hist_delta_.push_back(nbr_delta[static_cast<std::size_t>(k)]);
      }
    }
    hist_offset_[i + 1] = static_cast<std::int32_t>(hist_partner_.size());
  }
  reorder_parcels(keep);

  auto exchange_sized = [&] {
    // The sizes first (the receiver cannot know them), then the payload.
    std::vector<std::vector<double>> sizes(static_cast<std::size_t>(ranks)),
        got(static_cast<std::size_t>(ranks));
    for (int q = 0; q < ranks; ++q) {
      if (q == me) continue;
      sizes[static_cast<std::size_t>(q)] = {
          static_cast<double>(send_buf_[static_cast<std::size_t>(q)].size())};
      got[static_cast<std::size_t>(q)].resize(1);
    }
    comm.exchange(sizes, got);
    for (int q = 0; q < ranks; ++q) {
      recv_buf_[static_cast<std::size_t>(q)].resize(
          q == me ? 0 : static_cast<std::size_t>(got[static_cast<std::size_t>(q)][0]));
    }
    comm.exchange(send_buf_, recv_buf_);
    for (int q = 0; q < ranks; ++q) {
      const std::size_t sent = send_buf_[static_cast<std::size_t>(q)].size();
      counters_.doubles_sent += static_cast<long long>(sent);
      counters_.messages += sent > 0 ? 1 : 0;
    }
  };
  // Appends the parcels of every rank's message; ghosts are listed by their sender.
  const std::size_t head = packed_row_size() + 1;  // the row and its history length
  auto take_in = [&](bool ghosts) {
    for (int q = 0; q < ranks; ++q) {
      const std::vector<double>& b = recv_buf_[static_cast<std::size_t>(q)];
      const double* row = b.data();
      const double* end = b.data() + b.size();
      while (row < end) {
        if (row + head > end) throw std::runtime_error("ParcelSystem: a truncated parcel message");
        if (ghosts)
          recv_ghosts_[static_cast<std::size_t>(q)].push_back(static_cast<std::int32_t>(size()));
        row = append_packed(row, ghosts);
      }
    }
  };

  // 3. Take in the parcels that came to this rank.
  exchange_sized();
  take_in(false);
  // 4. Ghosts: this rank's parcels within reach of another rank's columns.
  for (auto& b : send_buf_) b.clear();
  for (std::size_t i = 0; i < size(); ++i) {
    const int cx = cell_column(x[i]);
    for (int q = 0; q < ranks; ++q) {
      if (q == me || !near_rank(cx, q)) continue;
      send_ghosts_[static_cast<std::size_t>(q)].push_back(static_cast<std::int32_t>(i));
      pack_parcel(i, false, send_buf_[static_cast<std::size_t>(q)]);
      ++counters_.ghosts_sent;
    }
  }
  exchange_sized();
  take_in(true);
  // 5. The table in the one-rank order; the exchange lists follow their rows.
  const std::vector<std::int32_t> by_key = sort_table_by_key();
  follow_rows(by_key);
  old_offset_ = hist_offset_;
  old_partner_id_ = hist_partner_;
  old_delta_ = hist_delta_;
  return had_list;
}

void ParcelSystem::after_distributed_sort(bool permuted) {
  if (!permuted) return;
  const SecondsSince timer(counters_.seconds);
  const std::size_t n = size();
  follow_rows(old_index_);
  // This rank's cells follow those of the ranks before it: its parcels take the next keys.
  const Communicator& comm = *comm_;
  const double mine = static_cast<double>(owned_count());
  std::vector<std::vector<double>> counts;
  comm.gather(std::span<const double>(&mine, 1), counts);
  std::vector<double> flat;
  if (comm.is_root()) {
    for (const auto& c : counts) flat.push_back(c.at(0));
  }
  comm.broadcast(flat);
  std::int64_t next = 0;
  for (int q = 0; q < comm.rank(); ++q)
    next += static_cast<std::int64_t>(flat.at(static_cast<std::size_t>(q)));
  for (std::size_t i = 0; i < n; ++i) {
    if (rank_copy[i] == 0) order_key[i] = next++;
  }
  // The ghosts learn their owners' new keys.
  const int ranks = comm.size();
  for (int q = 0; q < ranks; ++q) {
    auto& out = send_buf_[static_cast<std::size_t>(q)];
    out.clear();
    for (std::int32_t e : send_ghosts_[static_cast<std::size_t>(q)])
      out.push_back(static_cast<double>(order_key[static_cast<std::size_t>(e)]));
    recv_buf_[static_cast<std::size_t>(q)].resize(recv_ghosts_[static_cast<std::size_t>(q)].size());
  }
  comm.exchange(send_buf_, recv_buf_);
  for (int q = 0; q < ranks; ++q) {
    const auto& l = recv_ghosts_[static_cast<std::size_t>(q)];
    for (std::size_t k = 0; k < l.size(); ++k) {
      order_key[static_cast<std::size_t>(l[k])] =
          static_cast<std::int64_t>(recv_buf_[static_cast<std::size_t>(q)][k]);
    }
    counters_.doubles_sent += static_cast<long long>(send_buf_[static_cast<std::size_t>(q)].size());
    counters_.messages += send_buf_[static_cast<std::size_t>(q)].empty() ? 0 : 1;
  }
}

void ParcelSystem::refresh_ghosts(std::span<std::vector<double>* const> columns) {
  const SecondsSince timer(counters_.seconds);
  const int ranks = comm_->size();
  const std::size_t width = columns.size();
  for (int q = 0; q < ranks; ++q) {
    auto& out = send_buf_[static_cast<std::size_t>(q)];
    const auto& l = send_ghosts_[static_cast<std::size_t>(q)];
    out.resize(l.size() * width);
    for (std::size_t k = 0; k < l.size(); ++k) {
      for (std::size_t c = 0; c < width; ++c)
        out[k * width + c] = (*columns[c])[static_cast<std::size_t>(l[k])];
    }
    recv_buf_[static_cast<std::size_t>(q)].resize(recv_ghosts_[static_cast<std::size_t>(q)].size() *
                                                  width);
    counters_.doubles_sent += static_cast<long long>(out.size());
    counters_.messages += out.empty() ? 0 : 1;
  }
  comm_->exchange(send_buf_, recv_buf_);
  for (int q = 0; q < ranks; ++q) {
    const auto& in = recv_buf_[static_cast<std::size_t>(q)];
    const auto& l = recv_ghosts_[static_cast<std::size_t>(q)];
    for (std::size_t k = 0; k < l.size(); ++k) {
      for (std::size_t c = 0; c < width; ++c)
        (*columns[c])[static_cast<std::size_t>(l[k])] = in[k * width + c];
    }
  }
}

void ParcelSystem::refresh_ghost_kinematics() {
  std::vector<double>* const kinematics[] = {&x, &y, &vx, &vy, &omega};
  refresh_ghosts(kinematics);
}

void ParcelSystem::refresh_ghost_columns(std::span<const ParcelColumn> columns) {
  if (comm_ == nullptr) return;
  std::array<std::vector<double>*, 8> arrays{};
  if (columns.size() > arrays.size()) {
    throw std::invalid_argument("ParcelSystem::refresh_ghost_columns: at most 8 columns at once");
  }
  for (std::size_t k = 0; k < columns.size(); ++k) arrays[k] = &column(columns[k]);
  refresh_ghosts(std::span(arrays.data(), columns.size()));
}

double ParcelSystem::max_over_ranks(double value) const {
  return comm_ != nullptr ? -comm_->min(-value) : value;
}

void ParcelSystem::max_over_ranks(std::span<double> values) const {
  if (comm_ == nullptr) return;
  for (double& v : values) v = -v;
  comm_->min_each(values);
  for (double& v : values) v = -v;
}

std::string ParcelSystem::first_failure(const std::string& local) const {
  return comm_ != nullptr ? comm_->first_nonempty(local) : local;
}

void ParcelSystem::pack_owned(std::vector<double>& out, bool with_history,
                              const std::function<bool(std::size_t)>& keep) const {
  for (std::size_t i = 0; i < size(); ++i) {
    if (!is_ghost(i) && (!keep || keep(i))) pack_parcel(i, with_history, out);
  }
}

void ParcelSystem::assign_packed(const std::vector<std::vector<double>>& pieces) {
  // Start from an empty table with this system's columns.
  const std::vector<std::int32_t> none;
  order_key.resize(size());
  rank_copy.assign(size(), 0);
  x_build.resize(size());
  y_build.resize(size());
  hist_offset_.assign(size() + 1, 0);
  hist_partner_.clear();
  hist_delta_.clear();
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
}

}  // namespace dustlift
