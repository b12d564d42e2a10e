// GasSolver's checks of the state and the message naming the first cell that failed.
#include <cmath>
#include <sstream>

#include "solver/core/errors.hpp"
#include "solver/gas/gas_solver_impl.hpp"

namespace dustlift {

/// The checks of one cell after its primitives were set.
CellFault GasSolver::Impl::classify(std::size_t c, double pp) const {
  if (!(std::isfinite(U[Conserved::kMass].data()[c]) &&
        std::isfinite(U[Conserved::kMomentumX].data()[c]) &&
        std::isfinite(U[Conserved::kMomentumY].data()[c]) &&
        std::isfinite(U[Conserved::kEnergy].data()[c]))) {
    return CellFault::NotFinite;
  }
  if (!(rho.data()[c] > 0.0)) return CellFault::Density;
  if (!(pp > 0.0) || !std::isfinite(pp)) return CellFault::Pressure;
  return CellFault::None;
}

/// Which check cell (i, j) failed, for the message.
void GasSolver::Impl::record_fault(int j, int i) {
  const std::size_t c = at(i, j);
  fault_i[static_cast<std::size_t>(j)] = i;
  fault_kind[static_cast<std::size_t>(j)] = classify(c, p.data()[c]);
}

/// Checks the current primitives (as left by the last step or refresh_primitives(), e.g.
/// after the coupling changed the state) so a bad input is reported where it is, not
/// where its NaN spread to during the first stage.
void GasSolver::Impl::check_current_state() {
#pragma omp parallel for if (threaded) schedule(static)
  for (int j = 0; j < ny; ++j) {
    int first_fault = -1;
    CellFault kind = CellFault::None;
    for (int i = 0; i < nx && first_fault < 0; ++i) {
      const std::size_t c = at(i, j);
      bool finite = true;
      for (int k = 0; k < Conserved::kCount; ++k) finite = finite && std::isfinite(U[k].data()[c]);
      if (!finite) {
        kind = CellFault::NotFinite;
      } else if (!(rho.data()[c] > 0.0) || !(U[Conserved::kMass].data()[c] > 0.0)) {
        kind = CellFault::Density;
      } else if (!(p.data()[c] > 0.0)) {
        kind = CellFault::Pressure;
      }
      if (kind != CellFault::None) first_fault = i;
    }
    fault_i[static_cast<std::size_t>(j)] = first_fault;
    fault_kind[static_cast<std::size_t>(j)] = kind;
  }
  throw_on_fault();
}

void GasSolver::Impl::throw_on_fault() const {
  std::string message = fault_message();
  if (fault_reporting.agree) message = fault_reporting.agree(message);
  if (!message.empty()) throw NumericalFailure(message);
}

/// The first faulty row's cell, described ("" when no row has one).
std::string GasSolver::Impl::fault_message() const {
  for (int j = 0; j < ny; ++j) {
    const int i = fault_i[static_cast<std::size_t>(j)];
    if (i < 0) continue;
    const std::size_t c = at(i, j);
    std::ostringstream m;
    m.precision(6);
    m << "gas cell (i, j) = (" << i + fault_reporting.first_column << ", " << j
      << ") at x = " << grid.x().center(i) << " m, y = " << grid.y().center(j) << " m: ";
    switch (fault_kind[static_cast<std::size_t>(j)]) {
      case CellFault::NotFinite:
        m << "conserved variables not finite (a rho = " << U[Conserved::kMass].data()[c]
          << ", a rho u = " << U[Conserved::kMomentumX].data()[c]
          << ", a rho v = " << U[Conserved::kMomentumY].data()[c]
          << ", a E = " << U[Conserved::kEnergy].data()[c] << ")";
        break;
      case CellFault::Density:
        m << "density rho = " << rho.data()[c]
          << " kg/m^3 (a rho = " << U[Conserved::kMass].data()[c] << ") is not positive";
        break;
      default:
        m << "pressure p = " << p.data()[c] << " Pa is not positive (T = " << T.data()[c] << " K)";
        break;
    }
    return m.str();
  }
  return {};
}

}  // namespace dustlift
