#include "solver/parallel/slab_halo.hpp"

#include <chrono>

#include "solver/gas/gas_solver.hpp"

namespace dustlift {

SlabHalo::SlabHalo(const Communicator& comm, SlabLayout layout, const Grid2D& slab_grid)
    : comm_(comm),
      layout_(std::move(layout)),
      nx_(slab_grid.nx()),
      ny_(slab_grid.ny()),
      rows_(slab_grid.ny() + 2 * slab_grid.ghosts()),
      ng_(slab_grid.ghosts()),
      stride_(slab_grid.stride()),
      edge_updates_(slab_grid, 0.0) {}

void SlabHalo::attach(GasSolver& gas) {
  gas.set_ghost_filler(GridSide::Left, owns_left_boundary() ? nullptr : this);
  gas.set_ghost_filler(GridSide::Right, owns_right_boundary() ? nullptr : this);
  const Communicator& comm = comm_;
  gas.set_fault_reporting({layout_.first_column(), [&comm](const std::string& local) {
                             return comm.first_nonempty(local);
                           }});
  gas.set_rest_agreement({layout_.first_column(), layout_.bounds.back(),
                          [&comm](std::span<double> values) { comm.min_each(values); }});
}

void SlabHalo::fill(const PrimitiveGhosts& ghosts) {
  const auto& f = ghosts.fields;
  Field2D* const fields[] = {f[Primitive::kDensity],     f[Primitive::kVelocityX],
                             f[Primitive::kVelocityY],   f[Primitive::kPressure],
                             f[Primitive::kTemperature], &edge_updates_};
  // The updates ride along only where the solver skips resting cells (and so asks).
  const bool updates = ghosts.updated_lo != nullptr;
  if (updates) mark_edge_updates(ghosts.updated_lo, ghosts.updated_hi);
  exchange_columns(std::span<Field2D* const>(fields).first(updates ? 6 : 5));
}

void SlabHalo::fill_porosity(Field2D& alpha) {
  Field2D* const fields[] = {&alpha};
  exchange_columns(fields);
}

void SlabHalo::mark_edge_updates(const int* lo, const int* hi) {
  for (int j = 0; j < ny_; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const bool active = lo[k] < hi[k];
    const double left = active && lo[k] < ng_ ? 1.0 : 0.0;
    const double right = active && hi[k] > nx_ - ng_ ? 1.0 : 0.0;
    for (int g = 0; g < ng_; ++g) {
      edge_updates_(g, j) = left;
      edge_updates_(nx_ - 1 - g, j) = right;
    }
  }
}

bool SlabHalo::changed_beyond(GridSide side, int j0, int j1) const {
  if (!is_x_side(side)) return false;
  const int ghost_column = side == GridSide::Left ? -1 : nx_;
  bool changed = false;
  for (int r = j0; r < j1; ++r) changed = changed || edge_updates_(ghost_column, r) != 0.0;
  return changed;
}

void SlabHalo::exchange_columns(std::span<Field2D* const> fields) {
  const auto start = std::chrono::steady_clock::now();
  const int left = layout_.left(), right = layout_.right();
  const auto block = static_cast<std::size_t>(ng_) * static_cast<std::size_t>(rows_);
  send_.resize(block * fields.size());
  receive_.resize(block * fields.size());
  // Copies columns [c0, c0 + ng) of every row of every field to or from the buffer.
  auto pack = [&](int c0) {
    std::size_t k = 0;
    for (Field2D* f : fields) {
      for (int r = 0; r < rows_; ++r) {
        const double* row = f->data() +
                            static_cast<std::size_t>(r) * static_cast<std::size_t>(stride_) +
                            static_cast<std::size_t>(c0 + ng_);
        for (int g = 0; g < ng_; ++g) send_[k++] = row[g];
      }
    }
  };
  auto unpack = [&](int c0) {
    std::size_t k = 0;
    for (Field2D* f : fields) {
      for (int r = 0; r < rows_; ++r) {
        double* row = f->data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(stride_) +
                      static_cast<std::size_t>(c0 + ng_);
        for (int g = 0; g < ng_; ++g) row[g] = receive_[k++];
      }
    }
  };
  // Leftwards: my first columns become the left neighbour's right ghosts.
  if (left >= 0) pack(0);
  comm_.send_receive(left >= 0 ? std::span<const double>(send_) : std::span<const double>(), left,
                     right >= 0 ? std::span<double>(receive_) : std::span<double>(), right);
  if (right >= 0) unpack(nx_);
  // Rightwards: my last columns become the right neighbour's left ghosts.
  if (right >= 0) pack(nx_ - ng_);
  comm_.send_receive(right >= 0 ? std::span<const double>(send_) : std::span<const double>(), right,
                     left >= 0 ? std::span<double>(receive_) : std::span<double>(), left);
  if (left >= 0) unpack(-ng_);
  const long long sends = (left >= 0) + (right >= 0);
  messages_sent_ += sends;
  doubles_sent_ += sends * static_cast<long long>(send_.size());
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace dustlift
