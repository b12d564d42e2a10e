// The parcels on x-slabs of MPI ranks (docs/parallel.md).
//
// Exactness: a decomposed run gives the one-rank run's bits. Each parcel carries its index
// in the one-rank parcel order (order_key); every rank keeps its table in that order, so the
// neighbour lists, the contact sums and the cell sort visit parcels as one rank would. The
// cuts lie on neighbour-cell faces, and cells are numbered along y first, so after a
// permuting sort rank r's parcels are the one-rank order's positions [offset_r, offset_r +
// count_r): the new keys need only the counts of the ranks before. Rebuilds, the sub-step
// count and the cell size are decided collectively. A copy of another rank's parcel within
// contact reach is never integrated as its own: its forces are skipped and its state is its
// owner's after every sub-step.
#include "solver/parallel/parcel_slabs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>

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

ParcelSlabs::ParcelSlabs(const Communicator& comm) : comm_(&comm) {}

double ParcelSlabs::min(double value) const {
  return comm_->min(value);
}
bool ParcelSlabs::any(bool value) const {
  return comm_->any(value);
}

void ParcelSlabs::split(ParcelSystem& ps, std::vector<double> cuts) {
  if (ps.config().domain.periodic_x) {
    throw std::invalid_argument(
        "ParcelSystem: a periodic channel's parcels cannot be split over ranks");
  }
  if (ps.decomposed()) throw std::logic_error("ParcelSlabs::split: the parcels are split already");
  ps.decompose(*this);
  set_cuts(std::move(cuts));
  const std::size_t n = ps.size();
  ps.order_key.resize(n);
  std::iota(ps.order_key.begin(), ps.order_key.end(), std::int64_t{0});
  ps.rank_copy.assign(n, 0);
  const auto ranks = static_cast<std::size_t>(comm_->size());
  send_copies_.assign(ranks, {});
  recv_copies_.assign(ranks, {});
  send_buf_.assign(ranks, {});
  recv_buf_.assign(ranks, {});
  split_replicated(ps);
}

void ParcelSlabs::update_first_columns(const ParcelSystem& ps) {
  if (!ps.cells_along_y_first()) {
    throw std::invalid_argument(
        "ParcelSystem: parcels split over ranks need a domain longer than high");
  }
  // Each rank's first cell column: the cuts rounded to the nearest cell face.
  const int ranks = comm_->size();
  first_column_.assign(static_cast<std::size_t>(ranks) + 1, 0);
  for (int q = 1; q < ranks; ++q) {
    const double c = std::round(
        (cuts_[static_cast<std::size_t>(q - 1)] - ps.config().domain.x_min) / ps.cell_width());
    first_column_[static_cast<std::size_t>(q)] =
        std::max(first_column_[static_cast<std::size_t>(q - 1)],
                 static_cast<int>(std::clamp(c, 0.0, double(ps.cell_columns()))));
  }
  first_column_[static_cast<std::size_t>(ranks)] = ps.cell_columns();
}

int ParcelSlabs::copy_reach_columns(const ParcelSystem& ps) const {
  return static_cast<int>(std::ceil((ps.listing_reach() + copy_margin_) / ps.cell_width())) + 1;
}

void ParcelSlabs::split_replicated(ParcelSystem& ps) {
  // Every rank holds the same table: each keeps its own parcels, and as copies the others'
  // within reach of its columns and every listed partner of its own (a system split between
  // two rebuilds keeps its lists, so a restart continues bitwise).
  const SecondsSince timer(counters_.seconds);
  ps.update_cell_geometry();
  update_first_columns(ps);
  const int me = comm_->rank();
  const std::size_t n = ps.size();
  const int reach = copy_reach_columns(ps);
  const std::vector<int> owner = owners(ps);
  const std::vector<std::vector<std::uint8_t>> needed = held_by_rank(ps, owner, reach);
  const std::vector<std::uint8_t>& mine = needed[static_cast<std::size_t>(me)];
  std::vector<std::int32_t> keep, new_index(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (mine[i] == 0) continue;
    new_index[i] = static_cast<std::int32_t>(keep.size());
    keep.push_back(static_cast<std::int32_t>(i));
  }
  list_replicated_copies(owner, needed, new_index);
  const bool listed = ps.nbr_offset.size() == n + 1;
  if (listed) keep_own_lists(ps, owner, keep, new_index);
  for (std::size_t i = 0; i < n; ++i) ps.rank_copy[i] = owner[i] != me ? 1 : 0;
  ps.clear_carried_history();
  ps.reorder_parcels(keep);
  if (listed) {
    // Between rebuilds a copy never asks for one (as after a rebuild).
    ps.inv_skin2.resize(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ps.inv_skin2[i] = ps.rank_copy[i] != 0 ? 0.0 : 1.0 / (ps.half_skin[i] * ps.half_skin[i]);
    }
  }
}

std::vector<std::vector<std::uint8_t>> ParcelSlabs::held_by_rank(const ParcelSystem& ps,
                                                                 const std::vector<int>& owner,
                                                                 int reach) const {
  const int ranks = comm_->size();
  const std::size_t n = ps.size();
  std::vector<std::vector<std::uint8_t>> needed(static_cast<std::size_t>(ranks),
                                                std::vector<std::uint8_t>(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    const int column = ps.cell_column(ps.x[i]);
    for (int q = 0; q < ranks; ++q) {
      if (owner[i] == q || near_rank(column, q, reach)) needed[static_cast<std::size_t>(q)][i] = 1;
    }
  }
  if (ps.nbr_offset.size() == n + 1) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::int32_t k = ps.nbr_offset[i]; k < ps.nbr_offset[i + 1]; ++k) {
        needed[static_cast<std::size_t>(owner[i])]
              [static_cast<std::size_t>(ps.nbr_index[static_cast<std::size_t>(k)])] = 1;
      }
    }
  }
  return needed;
}

void ParcelSlabs::list_replicated_copies(const std::vector<int>& owner,
                                         const std::vector<std::vector<std::uint8_t>>& needed,
                                         const std::vector<std::int32_t>& new_index) {
  // In table order on both sides.
  const int ranks = comm_->size(), me = comm_->rank();
  const std::vector<std::uint8_t>& mine = needed[static_cast<std::size_t>(me)];
  for (std::size_t i = 0; i < owner.size(); ++i) {
    if (owner[i] == me) {
      for (int q = 0; q < ranks; ++q) {
        if (q != me && needed[static_cast<std::size_t>(q)][i] != 0) {
          send_copies_[static_cast<std::size_t>(q)].push_back(new_index[i]);
        }
      }
    } else if (mine[i] != 0) {
      recv_copies_[static_cast<std::size_t>(owner[i])].push_back(new_index[i]);
    }
  }
}

void ParcelSlabs::keep_own_lists(ParcelSystem& ps, const std::vector<int>& owner,
                                 const std::vector<std::int32_t>& keep,
                                 const std::vector<std::int32_t>& new_index) const {
  const int me = comm_->rank();
  std::vector<std::int32_t> offset(keep.size() + 1, 0), index;
  std::vector<std::int8_t> image;
  std::vector<double> delta;
  for (std::size_t k = 0; k < keep.size(); ++k) {
    const auto i = static_cast<std::size_t>(keep[k]);
    if (owner[i] == me) {
      for (std::int32_t s = ps.nbr_offset[i]; s < ps.nbr_offset[i + 1]; ++s) {
        const auto slot = static_cast<std::size_t>(s);
        index.push_back(new_index[static_cast<std::size_t>(ps.nbr_index[slot])]);
        image.push_back(ps.nbr_image[slot]);
        delta.push_back(ps.nbr_delta[slot]);
      }
    }
    offset[k + 1] = static_cast<std::int32_t>(index.size());
  }
  ps.nbr_offset.swap(offset);
  ps.nbr_index.swap(index);
  ps.nbr_image.swap(image);
  ps.nbr_delta.swap(delta);
}

void ParcelSlabs::set_cuts(std::vector<double> cuts) {
  if (cuts.size() + 1 != static_cast<std::size_t>(comm_->size())) {
    throw std::invalid_argument("ParcelSlabs::set_cuts: one cut between each two ranks");
  }
  for (std::size_t k = 1; k < cuts.size(); ++k) {
    if (!(cuts[k] >= cuts[k - 1]))
      throw std::invalid_argument("ParcelSlabs::set_cuts: cuts must ascend");
  }
  cuts_ = std::move(cuts);
}

int ParcelSlabs::owner_of_column(int cx) const {
  const auto it = std::upper_bound(first_column_.begin(), first_column_.end(), cx);
  return std::clamp(static_cast<int>(it - first_column_.begin()) - 1, 0, comm_->size() - 1);
}

void ParcelSlabs::follow_rows(const std::vector<std::int32_t>& old_of_new) {
  std::vector<std::int32_t> new_of_old(old_of_new.size());
  for (std::size_t k = 0; k < old_of_new.size(); ++k) {
    new_of_old[static_cast<std::size_t>(old_of_new[k])] = static_cast<std::int32_t>(k);
  }
  for (auto* lists : {&send_copies_, &recv_copies_}) {
    for (auto& l : *lists) {
      for (std::int32_t& e : l) e = new_of_old[static_cast<std::size_t>(e)];
    }
  }
}

std::vector<int> ParcelSlabs::owners(const ParcelSystem& ps) const {
  std::vector<int> owner(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) owner[i] = owner_of_column(ps.cell_column(ps.x[i]));
  return owner;
}

bool ParcelSlabs::near_rank(int cx, int q, int reach) const {
  return cx >= first_column_[static_cast<std::size_t>(q)] - reach &&
         cx < first_column_[static_cast<std::size_t>(q) + 1] + reach;
}

bool ParcelSlabs::redistribute(ParcelSystem& ps) {
  const SecondsSince timer(counters_.seconds);
  update_first_columns(ps);
  const std::size_t n0 = ps.size();
  const bool had_list = comm_->any(ps.nbr_offset.size() == n0 + 1);
  const std::vector<int> owner = owners(ps);
  // 1. Owned parcels leaving this rank, packed with their history (the list is still valid).
  pack_leaving(ps, owner, had_list);
  // 2. The rows that stay (owned and still ours), with their history as partner ids. The
  // reach is taken first: the leaving parcels' skins count.
  const int reach = copy_reach_columns(ps);
  const int me = comm_->rank();
  std::vector<std::int32_t> keep;
  keep.reserve(n0);
  for (std::size_t i = 0; i < n0; ++i) {
    if (ps.rank_copy[i] == 0 && owner[i] == me) keep.push_back(static_cast<std::int32_t>(i));
  }
  if (had_list && ps.nbr_offset.size() == n0 + 1) {
    ps.carry_listed_history();
  } else {
    ps.clear_carried_history();
  }
  ps.reorder_parcels(keep);
  // 3. Take in the parcels that came to this rank.
  exchange_sized();
  take_in(ps, false);
  // 4. Copies: this rank's parcels within reach of another rank's columns.
  pack_copies(ps, reach);
  exchange_sized();
  take_in(ps, true);
  // 5. The table in the one-rank order; the exchange lists follow their rows.
  follow_rows(ps.sort_table_by_key());
  return had_list;
}

void ParcelSlabs::pack_leaving(const ParcelSystem& ps, const std::vector<int>& owner,
                               bool had_list) {
  const int me = comm_->rank();
  const bool listed = ps.nbr_offset.size() == ps.size() + 1;
  for (auto& b : send_buf_) b.clear();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.rank_copy[i] != 0 || owner[i] == me) continue;
    ps.pack_parcel(i, had_list, send_buf_[static_cast<std::size_t>(owner[i])]);
    ++counters_.migrated;
    bool elongated = false;
    for (int w = 0; w < kWallCount; ++w)
      elongated = elongated || ps.wall_delta[i * kWallCount + static_cast<std::size_t>(w)] != 0.0;
    if (listed) {
      for (std::int32_t k = ps.nbr_offset[i]; k < ps.nbr_offset[i + 1]; ++k)
        elongated = elongated || ps.nbr_delta[static_cast<std::size_t>(k)] != 0.0;
    }
    counters_.migrated_with_history += elongated ? 1 : 0;
  }
}

void ParcelSlabs::pack_copies(const ParcelSystem& ps, int reach) {
  const int ranks = comm_->size(), me = comm_->rank();
  // The copy lists start anew (take_in lists the copies that come in).
  for (auto& l : send_copies_) l.clear();
  for (auto& l : recv_copies_) l.clear();
  for (auto& b : send_buf_) b.clear();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const int cx = ps.cell_column(ps.x[i]);
    for (int q = 0; q < ranks; ++q) {
      if (q == me || !near_rank(cx, q, reach)) continue;
      send_copies_[static_cast<std::size_t>(q)].push_back(static_cast<std::int32_t>(i));
      ps.pack_parcel(i, false, send_buf_[static_cast<std::size_t>(q)]);
      ++counters_.copies_sent;
    }
  }
}

void ParcelSlabs::exchange_sized() {
  // The sizes first (the receiver cannot know them), then the payload.
  const int ranks = comm_->size(), me = comm_->rank();
  std::vector<std::vector<double>> sizes(static_cast<std::size_t>(ranks)),
      got(static_cast<std::size_t>(ranks));
  for (int q = 0; q < ranks; ++q) {
    if (q == me) continue;
    sizes[static_cast<std::size_t>(q)] = {
        static_cast<double>(send_buf_[static_cast<std::size_t>(q)].size())};
    got[static_cast<std::size_t>(q)].resize(1);
  }
  comm_->exchange(sizes, got);
  for (int q = 0; q < ranks; ++q) {
    recv_buf_[static_cast<std::size_t>(q)].resize(
        q == me ? 0 : static_cast<std::size_t>(got[static_cast<std::size_t>(q)][0]));
  }
  comm_->exchange(send_buf_, recv_buf_);
  for (int q = 0; q < ranks; ++q) {
    const std::size_t sent = send_buf_[static_cast<std::size_t>(q)].size();
    counters_.doubles_sent += static_cast<long long>(sent);
    counters_.messages += sent > 0 ? 1 : 0;
  }
}

void ParcelSlabs::take_in(ParcelSystem& ps, bool copies) {
  const std::size_t head = ps.packed_row_size() + 1;  // the row and its history length
  for (int q = 0; q < comm_->size(); ++q) {
    const std::vector<double>& b = recv_buf_[static_cast<std::size_t>(q)];
    const double* row = b.data();
    const double* end = b.data() + b.size();
    while (row < end) {
      if (row + head > end) throw std::runtime_error("ParcelSlabs: a truncated parcel message");
      if (copies)
        recv_copies_[static_cast<std::size_t>(q)].push_back(static_cast<std::int32_t>(ps.size()));
      row = ps.append_packed(row, copies);
    }
  }
}

void ParcelSlabs::after_sort(ParcelSystem& ps, const std::vector<std::int32_t>& old_index,
                             bool permuted) {
  if (!permuted) return;
  const SecondsSince timer(counters_.seconds);
  const std::size_t n = ps.size();
  follow_rows(old_index);
  // This rank's cells follow those of the ranks before it: its parcels take the next keys.
  const Communicator& comm = *comm_;
  const double mine = static_cast<double>(ps.owned_count());
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
    if (ps.rank_copy[i] == 0) ps.order_key[i] = next++;
  }
  // The copies learn their owners' new keys.
  const int ranks = comm.size();
  for (int q = 0; q < ranks; ++q) {
    auto& out = send_buf_[static_cast<std::size_t>(q)];
    out.clear();
    for (std::int32_t e : send_copies_[static_cast<std::size_t>(q)])
      out.push_back(static_cast<double>(ps.order_key[static_cast<std::size_t>(e)]));
    recv_buf_[static_cast<std::size_t>(q)].resize(recv_copies_[static_cast<std::size_t>(q)].size());
  }
  comm.exchange(send_buf_, recv_buf_);
  for (int q = 0; q < ranks; ++q) {
    const auto& l = recv_copies_[static_cast<std::size_t>(q)];
    for (std::size_t k = 0; k < l.size(); ++k) {
      ps.order_key[static_cast<std::size_t>(l[k])] =
          static_cast<std::int64_t>(recv_buf_[static_cast<std::size_t>(q)][k]);
    }
    counters_.doubles_sent += static_cast<long long>(send_buf_[static_cast<std::size_t>(q)].size());
    counters_.messages += send_buf_[static_cast<std::size_t>(q)].empty() ? 0 : 1;
  }
}

void ParcelSlabs::refresh_copies(ParcelSystem& /*parcels*/,
                                 std::span<std::vector<double>* const> columns) {
  const SecondsSince timer(counters_.seconds);
  const int ranks = comm_->size();
  const std::size_t width = columns.size();
  for (int q = 0; q < ranks; ++q) {
    auto& out = send_buf_[static_cast<std::size_t>(q)];
    const auto& l = send_copies_[static_cast<std::size_t>(q)];
    out.resize(l.size() * width);
    for (std::size_t k = 0; k < l.size(); ++k) {
      for (std::size_t c = 0; c < width; ++c)
        out[k * width + c] = (*columns[c])[static_cast<std::size_t>(l[k])];
    }
    recv_buf_[static_cast<std::size_t>(q)].resize(recv_copies_[static_cast<std::size_t>(q)].size() *
                                                  width);
    counters_.doubles_sent += static_cast<long long>(out.size());
    counters_.messages += out.empty() ? 0 : 1;
  }
  comm_->exchange(send_buf_, recv_buf_);
  for (int q = 0; q < ranks; ++q) {
    const auto& in = recv_buf_[static_cast<std::size_t>(q)];
    const auto& l = recv_copies_[static_cast<std::size_t>(q)];
    for (std::size_t k = 0; k < l.size(); ++k) {
      for (std::size_t c = 0; c < width; ++c)
        (*columns[c])[static_cast<std::size_t>(l[k])] = in[k * width + c];
    }
  }
}

}  // namespace dustlift
