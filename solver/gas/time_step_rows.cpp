// Row kernel of the time-step limits (time_step_rows.hpp). Compiled with -fno-math-errno
// -fno-trapping-math (solver/CMakeLists.txt) so that sqrt and the selects vectorise.
#include "solver/gas/time_step_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/gas/thermo.hpp"
#include "solver/gas/transport.hpp"

namespace dustlift {
namespace {

/// cp(T) of each model, written so that a row loop vectorises (same values as cp()).
inline double cp_of(const CaloricallyPerfectGas& g, double T) {
  return g.cp(T);
}
inline double cp_of(const ThermallyPerfectAir& a, double T) {
  const double low = nasa7::cp_over_r(nasa7::kAirLow, T),
               high = nasa7::cp_over_r(nasa7::kAirHigh, T);
  return a.gas_constant() * (T < nasa7::kRangeBreak ? low : high);
}
/// gamma(T) as gamma() computes it, branch-free.
inline double gamma_of(const CaloricallyPerfectGas& g, double T) {
  return g.gamma(T);
}
inline double gamma_of(const ThermallyPerfectAir& a, double T) {
  const double c = cp_of(a, T);
  return c / (c - a.gas_constant());
}

}  // namespace

template <class Thermo>
void convective_rate_row(const Thermo& th, const TimeStepRow& r, double& max_rate,
                         GasExtremes& seen) {
  const double* __restrict u = r.u;
  const double* __restrict v = r.v;
  const double* __restrict T = r.T;
  const double* __restrict rho = r.rho;
  const double* __restrict idx = r.inv_dx;
  const double idy = r.inv_dy;
  const int n = r.n;
  const double R = th.gas_constant();
  double rate = max_rate, t_min = seen.t_min, t_max = seen.t_max, rho_min = seen.rho_min;
  // max and min are exact in any order, so the simd reductions give the same bits as a
  // scalar loop (GCC vectorises a floating-point max reduction only when told so).
#pragma omp simd reduction(max : rate, t_max) reduction(min : t_min, rho_min)
  for (int i = 0; i < n; ++i) {
    // c^2 = gamma R T (sound_speed_squared) with gamma = cp / (cp - R).
    const double t = T[i];
    const double cs = std::sqrt(gamma_of(th, t) * R * t);  // sound_speed_squared()
    const double cell_rate = (std::abs(u[i]) + cs) * idx[i] + (std::abs(v[i]) + cs) * idy;
    rate = rate < cell_rate ? cell_rate : rate;  // std::max(rate, cell_rate)
    t_max = t_max < t ? t : t_max;
    t_min = t < t_min ? t : t_min;
    rho_min = rho[i] < rho_min ? rho[i] : rho_min;
  }
  max_rate = rate;
  seen = {t_min, t_max, rho_min};
}

template <class Thermo>
void viscous_dt_row(const Thermo& th, const GordonWilkeAirTable& table, const TimeStepRow& r,
                    double& min_viscous_dt) {
  const double* __restrict T = r.T;
  const double* __restrict rho = r.rho;
  const double* __restrict idx = r.inv_dx;
  const double idy = r.inv_dy;
  const int n = r.n;
  table.apply(T, r.mu_scratch, r.lambda_scratch, n);  // the values operator() gives
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

template <class Thermo>
double viscous_dt_lower_bound(const Thermo& th, const GordonWilkeAirTable& table,
                              const GasExtremes& gas, double h2_min) {
  if (!(gas.t_min <= gas.t_max) || !(gas.rho_min > 0.0)) return 0.0;
  const TransportProperties most = table.largest_over(gas.t_min, gas.t_max);
  double cv_min = std::numeric_limits<double>::infinity();
  for (double t = std::floor(gas.t_min); t <= std::ceil(gas.t_max); t += 1.0)
    cv_min = std::min(cv_min, cp_of(th, t) - th.gas_constant());
  if (!(cv_min > 0.0) || !std::isfinite(most.mu) || !std::isfinite(most.lambda)) return 0.0;
  // mu max(1, gamma lambda / (mu cp)) = max(mu, lambda / cv).
  const double diffusivity = std::max(most.mu, most.lambda / cv_min);
  return 0.5 * 0.25 * h2_min * gas.rho_min / diffusivity;
}

template void convective_rate_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&,
                                                         const TimeStepRow&, double&, GasExtremes&);
template void viscous_dt_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&,
                                                    const GordonWilkeAirTable&, const TimeStepRow&,
                                                    double&);
template double viscous_dt_lower_bound<CaloricallyPerfectGas>(const CaloricallyPerfectGas&,
                                                              const GordonWilkeAirTable&,
                                                              const GasExtremes&, double);
template void convective_rate_row<ThermallyPerfectAir>(const ThermallyPerfectAir&,
                                                       const TimeStepRow&, double&, GasExtremes&);
template void viscous_dt_row<ThermallyPerfectAir>(const ThermallyPerfectAir&,
                                                  const GordonWilkeAirTable&, const TimeStepRow&,
                                                  double&);
template double viscous_dt_lower_bound<ThermallyPerfectAir>(const ThermallyPerfectAir&,
                                                            const GordonWilkeAirTable&,
                                                            const GasExtremes&, double);

}  // namespace dustlift
