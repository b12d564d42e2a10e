// Row kernel of the time-step limits (time_step_rows.hpp). Compiled with -fno-math-errno
// -fno-trapping-math (solver/CMakeLists.txt) so that sqrt and the selects vectorise.
#include "solver/gas/time_step_rows.hpp"

#include <algorithm>
#include <cmath>

#include "solver/gas/thermo.hpp"
#include "solver/gas/transport.hpp"

namespace dustlift {
namespace {

/// cp(T) of each model, written so that a row loop vectorises (same values as cp()).
inline double cp_of(const CaloricallyPerfectGas& g, double T) { return g.cp(T); }
inline double cp_of(const ThermallyPerfectAir& a, double T) {
  const double low = nasa7::cp_over_r(nasa7::kAirLow, T), high = nasa7::cp_over_r(nasa7::kAirHigh, T);
  return a.gas_constant() * (T < nasa7::kRangeBreak ? low : high);
}
/// gamma(T) as gamma() computes it, branch-free.
inline double gamma_of(const CaloricallyPerfectGas& g, double T) { return g.gamma(T); }
inline double gamma_of(const ThermallyPerfectAir& a, double T) {
  const double c = cp_of(a, T);
  return c / (c - a.gas_constant());
}

}  // namespace

template <class Thermo>
void time_step_row(const Thermo& th, const GordonWilkeAirTable* table, const TimeStepRow& r, double& max_rate,
                   double& min_viscous_dt) {
  const double* __restrict u = r.u;
  const double* __restrict v = r.v;
  const double* __restrict T = r.T;
  const double* __restrict rho = r.rho;
  const double* __restrict idx = r.inv_dx;
  const double idy = r.inv_dy;
  const int n = r.n;
  const double R = th.gas_constant();
  double rate = max_rate;
  // max and min are exact in any order, so the simd reductions give the same bits as a
  // scalar loop (GCC vectorises a floating-point max reduction only when told so).
#pragma omp simd reduction(max : rate)
  for (int i = 0; i < n; ++i) {
    // c^2 = gamma R T (sound_speed_squared) with gamma = cp / (cp - R).
    const double t = T[i];
    const double cs = std::sqrt(gamma_of(th, t) * R * t);  // sound_speed_squared()
    const double cell_rate = (std::abs(u[i]) + cs) * idx[i] + (std::abs(v[i]) + cs) * idy;
    rate = rate < cell_rate ? cell_rate : rate;  // std::max(rate, cell_rate)
  }
  max_rate = rate;
  if (table == nullptr) return;
  table->apply(T, r.mu_scratch, r.lambda_scratch, n);  // the values operator() gives
  const double* __restrict mu = r.mu_scratch;
  const double* __restrict lambda = r.lambda_scratch;
  double dt_min = min_viscous_dt;
#pragma omp simd reduction(min : dt_min)
  for (int i = 0; i < n; ++i) {
    const double t = T[i];
    const double cp = cp_of(th, t);
    const double gamma = gamma_of(th, t);
    const double factor = std::max(1.0, gamma * lambda[i] / (mu[i] * cp));
    const double h2 = std::min(1.0 / (idx[i] * idx[i]), 1.0 / (idy * idy));
    const double cell_dt = 0.25 * h2 * rho[i] / (mu[i] * factor);
    dt_min = cell_dt < dt_min ? cell_dt : dt_min;  // std::min(dt_min, cell_dt)
  }
  min_viscous_dt = dt_min;
}

template void time_step_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&, const GordonWilkeAirTable*,
                                                   const TimeStepRow&, double&, double&);
template void time_step_row<ThermallyPerfectAir>(const ThermallyPerfectAir&, const GordonWilkeAirTable*,
                                                 const TimeStepRow&, double&, double&);

}  // namespace dustlift
