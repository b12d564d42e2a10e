// GasSolver's stable time step: eq. (17) with the scheme's CFL, and a viscous limit.
#include <cmath>
#include <limits>

#include "solver/gas/gas_solver_impl.hpp"
#include "solver/gas/time_step_rows.hpp"

namespace dustlift {

template <class Th>
double GasSolver::Impl::stable_dt(const Th& th) const {
  ensure_scratch();
  double max_rate = 0.0;
  double min_viscous_dt = std::numeric_limits<double>::infinity();
  const double inf = std::numeric_limits<double>::infinity();
  double t_min = inf, t_max = -inf, rho_min = inf;
  const bool table = viscous && config.transport.model == TransportModel::GordonWilke;
  const auto row_of = [&](int j) {
    const std::size_t c0 = at(0, j);
    double* const sc = thread_scratch_base();
    return TimeStepRow{u.data() + c0,
                       v.data() + c0,
                       T.data() + c0,
                       rho.data() + c0,
                       inv_dx.data() + static_cast<std::size_t>(ng),
                       geo(inv_dy, j),
                       nx,
                       sc,
                       sc + scratch_len};
  };
  // clang-format off
#pragma omp parallel for if (threaded) schedule(static) \
    reduction(max : max_rate, t_max) reduction(min : min_viscous_dt, t_min, rho_min)
  // clang-format on
  for (int j = 0; j < ny; ++j) {
    const TimeStepRow row = row_of(j);
    GasExtremes seen{t_min, t_max, rho_min};
    convective_rate_row(th, row, max_rate, seen);
    t_min = seen.t_min;
    t_max = seen.t_max;
    rho_min = seen.rho_min;
    if (!viscous || table) continue;
    const double idy = row.inv_dy;
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = at(i, j);
      const double t = T.data()[c];
      const double idx = geo(inv_dx, i);
      const double cp = th.cp(t);
      const TransportProperties tp = transport_at(th, t);
      const double diffusivity_factor = std::max(1.0, th.gamma(t) * tp.lambda / (tp.mu * cp));
      const double h2 = std::min(1.0 / (idx * idx), 1.0 / (idy * idy));
      min_viscous_dt =
          std::min(min_viscous_dt, 0.25 * h2 * rho.data()[c] / (tp.mu * diffusivity_factor));
    }
  }
  const double convective_dt = config.scheme.cfl / max_rate;
  // The table's viscous limit is orders of magnitude above the convective one on cells of a
  // dust layer's size: where a bound from the gas's extremes shows it cannot be the smaller,
  // its pass (a table lookup and two divisions per cell) is left out; the step is the same.
  if (table && viscous_dt_lower_bound(th, air_table, {t_min, t_max, rho_min}, smallest_h2()) <
                   convective_dt) {
#pragma omp parallel for if (threaded) schedule(static) reduction(min : min_viscous_dt)
    for (int j = 0; j < ny; ++j) viscous_dt_row(th, air_table, row_of(j), min_viscous_dt);
  }
  return std::min(convective_dt, min_viscous_dt);
}

double GasSolver::stable_dt() const {
  return std::visit([&](const auto& th) { return impl_->stable_dt(th); }, impl_->thermo);
}

}  // namespace dustlift
