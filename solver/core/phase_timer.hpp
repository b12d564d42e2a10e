#pragma once
// Wall time per phase of a step, for the run log and the benchmarks (bench/paper_scene).
// A few clock reads per phase and step: far below the cost of any phase.
#include <chrono>

namespace dustlift {

/// Adds the wall time of its scope to `total` (seconds).
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace dustlift
