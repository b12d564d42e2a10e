#pragma once
// When recurring things happen in a run: outputs, probe samples, Catalyst deliveries,
// checkpoints and progress lines all keep one Cadence each. A cadence in simulated time is
// due at the multiples k * interval (the same products everywhere, time_targets.hpp, so a
// run restarted from a checkpoint meets the same times); one in steps at the multiples of n;
// one in wall time after so many seconds since it was last done.
#include <cmath>
#include <limits>

#include "solver/sim/time_targets.hpp"

namespace dustlift {

/// The moment a cadence is asked about.
struct RunClock {
  double time = 0.0;   ///< simulated s
  long long step = 0;  ///< steps taken
  double wall = 0.0;   ///< wall s since the run (segment) started
};

class Cadence {
 public:
  enum class Kind { Never, EveryStep, SimulatedTime, Steps, WallTime };

  /// Never due.
  Cadence() = default;
  static Cadence every_step() { return Cadence(Kind::EveryStep, 0.0); }
  /// At the multiples of `interval` simulated seconds (never for interval <= 0).
  static Cadence simulated(double interval) {
    return interval > 0.0 ? Cadence(Kind::SimulatedTime, interval) : Cadence();
  }
  /// At the steps that are multiples of n (never for n <= 0).
  static Cadence steps(long long n) {
    return n > 0 ? Cadence(Kind::Steps, static_cast<double>(n)) : Cadence();
  }
  /// `seconds` of wall time after it was last done (or started); never for seconds <= 0.
  static Cadence wall(double seconds) {
    return seconds > 0.0 ? Cadence(Kind::WallTime, seconds) : Cadence();
  }

  Kind kind() const { return kind_; }
  bool never() const { return kind_ == Kind::Never; }
  double interval() const { return interval_; }

  /// Starts counting at `now`: the next simulated multiple is the first after now.time (a
  /// restarted run does not repeat the one it stopped on); a wall cadence starts its timer.
  void start(const RunClock& now) {
    if (kind_ == Kind::SimulatedTime) next_ = first_multiple_after(now.time, interval_);
    last_wall_ = now.wall;
  }
  bool due(const RunClock& now) const {
    switch (kind_) {
      case Kind::Never:
        return false;
      case Kind::EveryStep:
        return true;
      case Kind::SimulatedTime:
        return now.time >= multiple_time(next_, interval_);
      case Kind::Steps:
        return now.step % static_cast<long long>(interval_) == 0;
      case Kind::WallTime:
        return now.wall - last_wall_ >= interval_;
    }
    return false;
  }
  /// Done at `now`: a simulated cadence goes on to the first multiple after now.time, a wall
  /// cadence counts from now.
  void done(const RunClock& now) {
    if (kind_ == Kind::SimulatedTime) next_ = first_multiple_after(now.time, interval_);
    last_wall_ = now.wall;
  }
  /// A simulated cadence's next time (the step that would pass it is shortened to end on
  /// it); infinity for the others.
  double next_time() const {
    return kind_ == Kind::SimulatedTime ? multiple_time(next_, interval_)
                                        : std::numeric_limits<double>::infinity();
  }
  /// The index k of the next simulated multiple (carried in checkpoints).
  long long next_index() const { return next_; }
  void set_next_index(long long k) { next_ = k; }

 private:
  Cadence(Kind kind, double interval) : kind_(kind), interval_(interval) {}
  Kind kind_ = Kind::Never;
  double interval_ = 0.0;
  long long next_ = 1;
  double last_wall_ = 0.0;
};

}  // namespace dustlift
