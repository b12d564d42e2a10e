#pragma once
// The convective and viscous time-step limits of eq. (17) over a row of cells, as a kernel
// that vectorises (GasSolver::stable_dt calls it per row).
#include "solver/gas/gas_config.hpp"

namespace dustlift {

class GordonWilkeAirTable;

struct TimeStepRow {
  const double* u;
  const double* v;
  const double* T;
  const double* rho;
  const double* inv_dx;  ///< per cell
  double inv_dy;
  int n;
  /// Scratch of n doubles each for the transport properties (used when viscous).
  double* mu_scratch = nullptr;
  double* lambda_scratch = nullptr;
};

/// The extremes of the rows' gas that bound the viscous limit (viscous_dt_lower_bound).
struct GasExtremes {
  double t_min, t_max, rho_min;
};

/// Raises max_rate to the largest (|u| + c)/dx + (|v| + c)/dy of the row, and widens `seen` to
/// the row's temperatures and densities.
template <class Thermo>
void convective_rate_row(const Thermo& thermo, const TimeStepRow& row, double& max_rate,
                         GasExtremes& seen);

/// Lowers min_viscous_dt to the row's smallest 0.25 h^2 rho / (mu max(1, gamma lambda / (mu cp)))
/// (Gordon-Wilke transport through `table`).
template <class Thermo>
void viscous_dt_row(const Thermo& thermo, const GordonWilkeAirTable& table, const TimeStepRow& row,
                    double& min_viscous_dt);

/// A lower bound of every cell's viscous limit, from the gas's extremes and the smallest
/// h^2 = min(dx^2, dy^2) of any cell: 0.25 h2_min rho_min / max(mu, gamma lambda / cp), with mu
/// and lambda the table's largest over [t_min, t_max] and gamma / cp = 1 / cv its largest there
/// (1 K steps), halved for what varies between those steps. Where it is above the convective
/// limit, the viscous one cannot be the smaller, and its cells need not be visited.
template <class Thermo>
double viscous_dt_lower_bound(const Thermo& thermo, const GordonWilkeAirTable& table,
                              const GasExtremes& gas, double h2_min);

}  // namespace dustlift
