#pragma once
// The few collective and neighbour operations the decomposed run needs, behind an
// interface: the physics and the driver see only this (solver/parallel/world.hpp makes the
// program's world; nothing outside solver/parallel/mpi/ includes mpi.h, and a build without
// MPI links the same code with a one-rank world).
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace dustlift {

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool is_root() const { return rank() == 0; }

  /// Reductions over all ranks (exact: a min, an integer sum, a logical or).
  virtual double min(double value) const = 0;
  /// Element by element: every rank's `values` become the minimum over the ranks (one
  /// allreduce; every rank passes as many).
  virtual void min_each(std::span<double> values) const = 0;
  virtual long long sum(long long value) const = 0;
  virtual bool any(bool value) const = 0;
  /// The text of the lowest-numbered rank whose text is not empty ("" when all are).
  virtual std::string first_nonempty(const std::string& text) const = 0;
  /// Sends `send` to rank `to` and receives `receive` from rank `from` (either may be -1:
  /// nothing to send or to receive). `receive` must be sized by the caller.
  virtual void send_receive(std::span<const double> send, int to, std::span<double> receive,
                            int from) const = 0;
  /// Root receives every rank's `piece` (root's own included), in rank order, into
  /// `pieces` (resized); the other ranks' `pieces` are left alone.
  /// Every rank sends send[q] to rank q and receives receive[q] from rank q, sized by the
  /// caller (empty: no message); all at once (a move of the slab cuts).
  virtual void exchange(const std::vector<std::vector<double>>& send,
                        std::vector<std::vector<double>>& receive) const = 0;
  virtual void gather(std::span<const double> piece,
                      std::vector<std::vector<double>>& pieces) const = 0;
  /// Rank 0's `values` to every rank (resized there).
  virtual void broadcast(std::vector<double>& values) const = 0;
  virtual void barrier() const = 0;
  /// Ends every rank's process with this exit code (an error only one rank met).
  [[noreturn]] virtual void abort(int code) const = 0;
};

/// One rank on its own: the serial run's communicator.
class SingleRank final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  double min(double value) const override { return value; }
  void min_each(std::span<double>) const override {}
  long long sum(long long value) const override { return value; }
  bool any(bool value) const override { return value; }
  std::string first_nonempty(const std::string& text) const override { return text; }
  void send_receive(std::span<const double>, int, std::span<double>, int) const override {}
  void exchange(const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& receive) const override {
    receive.resize(1);
    receive[0] = send.empty() ? std::vector<double>() : send[0];
  }
  void gather(std::span<const double> piece,
              std::vector<std::vector<double>>& pieces) const override {
    pieces.assign(1, std::vector<double>(piece.begin(), piece.end()));
  }
  void broadcast(std::vector<double>&) const override {}
  void barrier() const override {}
  [[noreturn]] void abort(int code) const override { std::exit(code); }
};

}  // namespace dustlift
