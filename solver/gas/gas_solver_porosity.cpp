// GasSolver's porosity: the initial one, and its changes as the particles move.
#include <cmath>

#include "solver/gas/gas_solver_impl.hpp"

namespace dustlift {

/// See GasSolver::change_porosity.
template <class Th>
void GasSolver::Impl::change_porosity(const Th& th, const Field2D& alpha_new, int j0, int j1) {
  j0 = std::max(j0, 0);
  j1 = std::min(j1, ny);
#pragma omp parallel if (threaded)
  {
    // Rows one at a time: the rows whose porosity changed (the layer's) are a few at the
    // bottom, and a static split gave them all to one thread. Rows are independent.
#pragma omp for schedule(dynamic, 1)
    for (int j = j0; j < j1; ++j) {
      const StageScratch sc = stage_scratch();
      fault_i[static_cast<std::size_t>(j)] = -1;
      int first = nx, last = -1;
      for (int i = 0; i < nx; ++i) {
        const std::size_t c = at(i, j);
        const double a_new = alpha_new.data()[c], a_old = alpha.data()[c];
        sc.changed[i] = 0.0;
        if (a_new == a_old) continue;
        // alpha rho and alpha rho u are kept; the internal energy follows the isentropic
        // compression by the volume the particles took or gave back: to first order exactly
        // the -p d(alpha_g) work of eq. (3), and unlike the linear form it cannot drive the
        // internal energy negative when alpha_g changes by a large fraction in one step.
        const double m = U[Conserved::kMass].data()[c], mx = U[Conserved::kMomentumX].data()[c],
                     my = U[Conserved::kMomentumY].data()[c];
        const double kinetic = 0.5 * (mx * mx + my * my) / m;
        const double g = th.gamma(T.data()[c]);
        U[Conserved::kEnergy].data()[c] = kinetic + (U[Conserved::kEnergy].data()[c] - kinetic) *
                                                        std::pow(a_old / a_new, g - 1.0);
        alpha.data()[c] = a_new;
        sc.changed[i] = 1.0;
        first = std::min(first, i);
        last = i;
      }
      if (last < first) continue;
      cells_changed(j, last + 1);
      StageScratch shifted = sc;
      shifted.changed = sc.changed + first;
      const int bad = primitives_row(th, primitive_row(j, first, last + 1), shifted);
      if (bad >= 0) record_fault(j, first + bad);
    }
  }
  fill_porosity_ghosts();
  fill_ghosts();
  throw_on_fault();
}

void GasSolver::initialize_porosity(const Field2D& alpha_g) {
  Impl& m = *impl_;
  m.state_written();
  for (int j = 0; j < m.ny; ++j) {
    for (int i = 0; i < m.nx; ++i) {
      const double a = alpha_g(i, j);
      const double scale = a / m.alpha(i, j);
      for (int k = 0; k < Conserved::kCount; ++k) m.U[static_cast<std::size_t>(k)](i, j) *= scale;
      m.alpha(i, j) = a;
    }
  }
  m.fill_porosity_ghosts();
}

void GasSolver::change_porosity(const Field2D& alpha_g, int j0, int j1) {
  std::visit([&](const auto& th) { impl_->change_porosity(th, alpha_g, j0, j1); }, impl_->thermo);
}

}  // namespace dustlift
