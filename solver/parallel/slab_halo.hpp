#pragma once
// GasHalo over a Communicator: the ghost columns a slab shares with its neighbours, all
// fields of one exchange in one message per direction.
#include <vector>

#include "solver/gas/gas_halo.hpp"
#include "solver/parallel/communicator.hpp"
#include "solver/parallel/slab_decomposition.hpp"

namespace dustlift {

class SlabHalo final : public GasHalo {
 public:
  SlabHalo(const Communicator& comm, SlabLayout layout, const Grid2D& slab_grid);

  bool owns_left_boundary() const override { return layout_.owns_left_boundary(); }
  bool owns_right_boundary() const override { return layout_.owns_right_boundary(); }
  int first_column() const override { return layout_.first_column(); }
  void exchange_columns(std::span<Field2D* const> fields) override;
  std::string first_failure(const std::string& local) override {
    return comm_.first_nonempty(local);
  }

  /// Doubles and messages this rank has sent (for the scaling model of docs/parallel.md).
  long long doubles_sent() const { return doubles_sent_; }
  long long messages_sent() const { return messages_sent_; }
  /// Wall seconds spent in exchange_columns (the transfer and any wait for a slower neighbour).
  double seconds() const { return seconds_; }

 private:
  const Communicator& comm_;
  SlabLayout layout_;
  int nx_ = 0, rows_ = 0, ng_ = 0, stride_ = 0;
  std::vector<double> send_, receive_;
  long long doubles_sent_ = 0, messages_sent_ = 0;
  double seconds_ = 0.0;
};

}  // namespace dustlift
