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
  const bool table = viscous && config.transport.model == TransportModel::GordonWilke;
  // clang-format off
#pragma omp parallel for if (threaded) schedule(static) \
    reduction(max : max_rate) reduction(min : min_viscous_dt)
  // clang-format on
  for (int j = 0; j < ny; ++j) {
    const double idy = geo(inv_dy, j);
    const std::size_t c0 = at(0, j);
    double* const sc = thread_scratch_base();
    const TimeStepRow row{u.data() + c0,
                          v.data() + c0,
                          T.data() + c0,
                          rho.data() + c0,
                          inv_dx.data() + static_cast<std::size_t>(ng),
                          idy,
                          nx,
                          sc,
                          sc + scratch_len};
    time_step_row(th, table ? &air_table : nullptr, row, max_rate, min_viscous_dt);
    if (!viscous || table) continue;
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
  return std::min(config.scheme.cfl / max_rate, min_viscous_dt);
}

double GasSolver::stable_dt() const {
  return std::visit([&](const auto& th) { return impl_->stable_dt(th); }, impl_->thermo);
}

}  // namespace dustlift
