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

/// Raises max_rate to the largest (|u| + c)/dx + (|v| + c)/dy of the row and, when `viscous`
/// (Gordon-Wilke transport through `table`), lowers min_viscous_dt to the smallest
/// 0.25 h^2 rho / (mu max(1, gamma lambda / (mu cp))).
template <class Thermo>
void time_step_row(const Thermo& thermo, const GordonWilkeAirTable* table, const TimeStepRow& row, double& max_rate,
                   double& min_viscous_dt);

}  // namespace dustlift
