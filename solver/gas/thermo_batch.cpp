// Row-batched temperature solve of thermally perfect air (thermo.hpp). Compiled with
// -fno-math-errno -fno-trapping-math (solver/CMakeLists.txt) so that the branch-free Newton
// steps vectorise; neither option changes a computed value.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/gas/thermo.hpp"

namespace dustlift {
namespace {

/// Two Newton steps on e(T) = e from the guess, all ranges by selects; NaN marks "not
/// converged" (then the caller uses the safeguarded solve). LowOnly: the low range alone,
/// valid when every iterate stays below the range break; returns the largest iterate so
/// that the caller can check it.
template <bool LowOnly>
[[gnu::noinline]] double two_newton_steps(const double* __restrict e, const double* __restrict guess,
                                          double* __restrict T, int n, double R, double e_min, double e_max,
                                          double t_min, double t_max) {
  using nasa7::kAirHigh;
  using nasa7::kAirLow;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double largest = 0.0;
  for (int i = 0; i < n; ++i) {
    const double target = e[i];
    const double g = guess[i];
    double t = (g > t_min && g < t_max) ? g : 300.0;
    double step = 0.0;
    double top = t;
    for (int it = 0; it < 2; ++it) {
      double h, cp;
      if constexpr (LowOnly) {
        h = nasa7::h_over_r(kAirLow, t);
        cp = nasa7::cp_over_r(kAirLow, t);
      } else {
        const bool low = t < nasa7::kRangeBreak;
        const double h_low = nasa7::h_over_r(kAirLow, t), h_high = nasa7::h_over_r(kAirHigh, t);
        const double cp_low = nasa7::cp_over_r(kAirLow, t), cp_high = nasa7::cp_over_r(kAirHigh, t);
        h = low ? h_low : h_high;
        cp = low ? cp_low : cp_high;
      }
      const double f = R * (h - kAirLow.a[5] - t) - target;
      const double next = t - f / (R * (cp - 1.0));
      step = next - t;
      t = next;
      top = std::max(top, it == 0 ? t : top);  // the iterates whose range was used: guess, first
    }
    largest = std::max(largest, top);
    const bool ok = std::abs(step) <= 1e-7 * t && t > t_min && t < t_max && target > e_min && target < e_max;
    T[i] = ok ? t : nan;
  }
  return largest;
}

}  // namespace

void ThermallyPerfectAir::temperatures(const double* e, const double* guess, double* T, int n) const {
  // The low range alone gives the same iterates while every polynomial evaluation is below
  // the break (the selects would pick it): try that first, redo the row if it was not so.
  const double largest = two_newton_steps<true>(e, guess, T, n, R_, e_min_, e_max_, kTmin, kTmax);
  if (!(largest < nasa7::kRangeBreak)) two_newton_steps<false>(e, guess, T, n, R_, e_min_, e_max_, kTmin, kTmax);
  for (int i = 0; i < n; ++i) {
    if (!(T[i] == T[i])) T[i] = temperature(e[i], guess[i]);
  }
}

}  // namespace dustlift
