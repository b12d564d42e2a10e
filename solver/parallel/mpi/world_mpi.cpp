// The Communicator over MPI_COMM_WORLD (built only when CMake finds MPI).
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "solver/parallel/world.hpp"

namespace dustlift {
namespace {

bool mpi_running() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized != 0 && finalized == 0;
}

class WorldCommunicator final : public Communicator {
 public:
  WorldCommunicator() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  double min(double value) const override {
    double out = value;
    MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    return out;
  }
  void min_each(std::span<double> values) const override {
    MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MIN,
                  MPI_COMM_WORLD);
  }
  long long sum(long long value) const override {
    long long out = value;
    MPI_Allreduce(&value, &out, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    return out;
  }
  bool any(bool value) const override {
    int in = value ? 1 : 0, out = 0;
    MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return out != 0;
  }
  std::string first_nonempty(const std::string& text) const override {
    // The lowest rank with a text, then its text to everyone.
    const int mine = text.empty() ? size_ : rank_;
    int first = size_;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == size_) return {};
    int length = rank_ == first ? static_cast<int>(text.size()) : 0;
    MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
    std::string out = rank_ == first ? text : std::string(static_cast<std::size_t>(length), ' ');
    MPI_Bcast(out.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
    return out;
  }
  void send_receive(std::span<const double> send, int to, std::span<double> receive,
                    int from) const override {
    MPI_Sendrecv(send.data(), static_cast<int>(send.size()), MPI_DOUBLE,
                 to < 0 ? MPI_PROC_NULL : to, kTag, receive.data(),
                 static_cast<int>(receive.size()), MPI_DOUBLE, from < 0 ? MPI_PROC_NULL : from,
                 kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  void exchange(const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& receive) const override {
    std::vector<MPI_Request> requests;
    receive.resize(static_cast<std::size_t>(size_));
    for (int q = 0; q < size_; ++q) {
      std::vector<double>& r = receive[static_cast<std::size_t>(q)];
      if (r.empty()) continue;
      requests.emplace_back();
      MPI_Irecv(r.data(), static_cast<int>(r.size()), MPI_DOUBLE, q, kTag + 1, MPI_COMM_WORLD,
                &requests.back());
    }
    for (int q = 0; q < size_ && q < static_cast<int>(send.size()); ++q) {
      const std::vector<double>& s = send[static_cast<std::size_t>(q)];
      if (s.empty()) continue;
      requests.emplace_back();
      MPI_Isend(s.data(), static_cast<int>(s.size()), MPI_DOUBLE, q, kTag + 1, MPI_COMM_WORLD,
                &requests.back());
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  }
  void gather(std::span<const double> piece,
              std::vector<std::vector<double>>& pieces) const override {
    int count = static_cast<int>(piece.size());
    std::vector<int> counts(static_cast<std::size_t>(size_)),
        offsets(static_cast<std::size_t>(size_));
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<double> all;
    if (rank_ == 0) {
      int total = 0;
      for (int r = 0; r < size_; ++r) {
        offsets[static_cast<std::size_t>(r)] = total;
        total += counts[static_cast<std::size_t>(r)];
      }
      all.resize(static_cast<std::size_t>(total));
    }
    MPI_Gatherv(piece.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (rank_ != 0) return;
    pieces.resize(static_cast<std::size_t>(size_));
    for (int r = 0; r < size_; ++r) {
      const auto b = all.begin() + offsets[static_cast<std::size_t>(r)];
      pieces[static_cast<std::size_t>(r)].assign(b, b + counts[static_cast<std::size_t>(r)]);
    }
  }
  void broadcast(std::vector<double>& values) const override {
    long long n = static_cast<long long>(values.size());
    MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
    values.resize(static_cast<std::size_t>(n));
    // In pieces below 2^31 elements (MPI's int counts).
    constexpr long long kPiece = 1LL << 28;
    for (long long k = 0; k < n; k += kPiece) {
      MPI_Bcast(values.data() + k, static_cast<int>(std::min(kPiece, n - k)), MPI_DOUBLE, 0,
                MPI_COMM_WORLD);
    }
  }
  void barrier() const override { MPI_Barrier(MPI_COMM_WORLD); }
  [[noreturn]] void abort(int code) const override {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
  }

 private:
  static constexpr int kTag = 12;
  int rank_ = 0, size_ = 1;
};

}  // namespace

/// Whether an MPI launcher started this process (mpirun/mpiexec of Open MPI or MPICH, or
/// srun with PMI/PMIx). A plain `dustlift run` does not initialise MPI at all: a singleton
/// MPI_Init would start Open MPI's runtime for nothing and slow every serial run.
bool started_by_launcher() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"}) {
    if (std::getenv(v) != nullptr) return true;
  }
  return false;
}

ParallelSession::ParallelSession(int& argc, char**& argv) {
  if (mpi_running() || !started_by_launcher()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  started_ = true;
  if (provided < MPI_THREAD_FUNNELED)
    throw std::runtime_error("MPI does not provide MPI_THREAD_FUNNELED");
}

ParallelSession::~ParallelSession() {
  if (started_ && mpi_running()) MPI_Finalize();
}

std::unique_ptr<Communicator> make_world_communicator() {
  if (!mpi_running()) return std::make_unique<SingleRank>();
  return std::make_unique<WorldCommunicator>();
}

bool built_with_mpi() {
  return true;
}

}  // namespace dustlift
