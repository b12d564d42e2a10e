#pragma once
// The times a run lands on: output k at k * interval (the same product everywhere, so an
// output time is one double whether the run was interrupted or not).
#include <cmath>

namespace dustlift {

/// Time of multiple k of `interval`.
inline double multiple_time(long long k, double interval) { return static_cast<double>(k) * interval; }

/// The smallest k >= 1 whose multiple_time(k, interval) is after `t` (interval > 0). The
/// division only guesses: k is corrected against the products themselves, so a time that
/// landed on multiple k gives k + 1, not k (0.00015 / 5e-5 = 2.9999999999999996).
inline long long first_multiple_after(double t, double interval) {
  long long k = static_cast<long long>(std::floor(t / interval));
  if (k < 0) k = 0;
  while (k > 0 && multiple_time(k, interval) > t) --k;
  while (multiple_time(k, interval) <= t) ++k;
  return k < 1 ? 1 : k;
}

/// The time a run ends at: `end`, or the output time it stands for when it lies within
/// 1e-9 intervals of one (end = 1.5e-4 with outputs every 5e-5 means 3 * 5e-5 =
/// 1.5000000000000002e-4, the output time, not a second time one rounding below it).
inline double end_target(double end, double interval) {
  if (!(interval > 0.0)) return end;
  const long long k = std::llround(end / interval);
  const double output = multiple_time(k, interval);
  return k > 0 && std::abs(output - end) <= 1e-9 * interval ? output : end;
}

}  // namespace dustlift
