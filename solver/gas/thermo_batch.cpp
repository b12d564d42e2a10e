// Row-batched temperature solve of thermally perfect air (thermo.hpp). Compiled with
// -fno-math-errno -fno-trapping-math (solver/CMakeLists.txt) so that the branch-free Newton
// steps vectorise; neither option changes a computed value.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/gas/thermo.hpp"

namespace dustlift {
namespace {

/// Newton step on e(T) = e at t (all ranges by selects unless LowOnly).
template <bool LowOnly>
inline double newton_iterate(double t, double target, double R) {
  using nasa7::kAirHigh;
  using nasa7::kAirLow;
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
  return t - f / (R * (cp - 1.0));
}

/// Two Newton steps on e(T) = e from the guess; NaN marks "not converged" (then the caller
/// uses the safeguarded solve). LowOnly: the low range alone, valid when every iterate whose
/// range was used (the guess and the first) stays below the range break; where one did not,
/// T is set to -1 (never a solution: a converged T is above t_min > 0) so that the caller
/// redoes the row (a NaN iterate gives a NaN T, i.e. the safeguarded solve). A per-cell
/// marker rather than a reduction, and selects rather than && chains, keep the loop
/// vectorisable.
template <bool LowOnly>
[[gnu::noinline]] void two_newton_steps(const double* __restrict e, const double* __restrict guess,
                                        double* __restrict T, int n, double R, double e_min, double e_max,
                                        double t_min, double t_max) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < n; ++i) {
    const double target = e[i];
    const double g = guess[i];
    const double t0 = ((g > t_min) & (g < t_max)) ? g : 300.0;  // & not &&: no branches, so it vectorises
    const double t1 = newton_iterate<LowOnly>(t0, target, R);
    const double t2 = newton_iterate<LowOnly>(t1, target, R);
    const bool ok = (std::abs(t2 - t1) <= 1e-7 * t2) & (t2 > t_min) & (t2 < t_max) & (target > e_min) & (target < e_max);
    const double solution = ok ? t2 : nan;
    if constexpr (LowOnly) {
      const bool below = std::max(t0, t1) < nasa7::kRangeBreak;
      T[i] = below ? solution : -1.0;
    } else {
      T[i] = solution;
    }
  }
}

/// Whether two_newton_steps<true> marked a cell of the row as beyond the low range.
[[gnu::noinline]] bool any_marked_beyond_low_range(const double* __restrict T, int n) {
  int marked = 0;
  for (int i = 0; i < n; ++i) marked |= T[i] < 0.0 ? 1 : 0;
  return marked != 0;
}

}  // namespace

void ThermallyPerfectAir::temperatures(const double* e, const double* guess, double* T, int n) const {
  // The low range alone gives the same iterates while every polynomial evaluation is below
  // the break (the selects would pick it): try that first, redo the row if it was not so.
  two_newton_steps<true>(e, guess, T, n, R_, e_min_, e_max_, kTmin, kTmax);
  if (any_marked_beyond_low_range(T, n)) two_newton_steps<false>(e, guess, T, n, R_, e_min_, e_max_, kTmin, kTmax);
  for (int i = 0; i < n; ++i) {
    if (!(T[i] == T[i])) T[i] = temperature(e[i], guess[i]);
  }
}

}  // namespace dustlift
