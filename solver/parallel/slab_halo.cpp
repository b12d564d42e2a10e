#include "solver/parallel/slab_halo.hpp"

#include <chrono>

namespace dustlift {

SlabHalo::SlabHalo(const Communicator& comm, SlabLayout layout, const Grid2D& slab_grid)
    : comm_(comm),
      layout_(std::move(layout)),
      nx_(slab_grid.nx()),
      rows_(slab_grid.ny() + 2 * slab_grid.ghosts()),
      ng_(slab_grid.ghosts()),
      stride_(slab_grid.stride()) {}

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
