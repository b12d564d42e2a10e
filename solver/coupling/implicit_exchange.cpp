// The implicit exchange factors of a CFD step (see apply_implicit_exchange in
// gas_particle_coupling.hpp): per cell from the sums of its parcels' sampled drag and heat
// coefficients and their capacities, then per parcel as its stencil's average.
#include <stdexcept>

#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/coupling/gas_properties.hpp"

namespace dustlift {

void GasParticleCoupling::apply_implicit_exchange(const GasSolver& gas, ParcelSystem& ps,
                                                  double dt) {
  const std::size_t active = stepped_.count;
  int j0 = 0, j1 = 0;
  row_range(ps, j0, j1);
  // The stencils are current since the last deposit, unless there was none.
  stencils_.update(grid_, slab(), ps, ps.size());
  // The stepped parcels read the cells of columns [0, c]; those sum every parcel reaching them.
  const int c = active < ps.size()
                    ? (active == 0 ? -1 : stencils_.column_bound(grid_, stepped_.x_max))
                    : grid_.nx() - 1;
  const std::size_t reaching = c < 0 ? 0 : stencils_.parcels_reaching(grid_, ps, c);
  clear_rows(grid_, implicit_.data(), j1, c + 1);
  stencils_.plan(grid_, reaching);
  // The stiff coefficients: drag's (momentum) and the heat transfer's, when they are on.
  const auto& momentum = effects_.stiff_momentum();
  const auto& heat = effects_.stiff_heat();
  if (momentum.size() > 1 || heat.size() > 1)
    throw std::logic_error("implicit exchange: one stiff coefficient per exchange at most");
  const double* K_raw = momentum.empty() ? nullptr : ps.column(momentum[0].sampled).data();
  const double* H_raw = heat.empty() ? nullptr : ps.column(heat[0].sampled).data();
  double* K = momentum.empty() ? nullptr : ps.column(momentum[0].applied).data();
  double* H = heat.empty() ? nullptr : ps.column(heat[0].applied).data();
  sum_implicit_cells(ps, c, K_raw, H_raw);
  implicit_factors(gas, dt, j1, c + 1);
  if (slab_) share_implicit_factors(j1);
  scale_by_implicit_factors(ps, active, K, H);
}

void GasParticleCoupling::sum_implicit_cells(const ParcelSystem& ps, int c, const double* K_raw,
                                             const double* H_raw) {
  // Per-cell sums over all parcels (the resting ones' samples are current), each in parcel
  // order (thread-independent).
  const double c_p = dem_cfg_.heat_capacity;
  const double* n_real = ps.n_real.data();
  const double* mass = ps.mass.data();
  stencils_.run([&](std::size_t k, int m) {
    const DepositStencil& st = stencils_[k];
    const int i = st.i[static_cast<std::size_t>(m)], j = st.j[static_cast<std::size_t>(m)];
    if (i > c) return;
    const double f = st.fraction[static_cast<std::size_t>(m)];
    ImplicitExchangeCell& r = implicit_[grid_.index(i, j)];
    if (K_raw != nullptr) r.drag += f * (n_real[k] * K_raw[k]);
    if (H_raw != nullptr) r.heat += f * (n_real[k] * H_raw[k]);
    r.mass += f * mass[k];
    r.heat_capacity += f * mass[k] * c_p;
  });
}

void GasParticleCoupling::implicit_factors(const GasSolver& gas, double dt, int j1, int nx) {
  const Field2D& gas_mass_density = gas.conserved(0);  // alpha_g rho
  const GasPrimitives g = gas.primitives();
  // Rows one at a time: the cells holding parcels are mostly in the layer's few rows at the
  // bottom, which a static split gave to one thread. Every cell on its own.
#pragma omp parallel for schedule(dynamic, \
                                  1) if (static_cast <std::size_t>(j1) * nx >= kParallelMinimum)
  for (int j = 0; j < j1; ++j) {
    for (int i = 0; i < nx; ++i) {
      ImplicitExchangeCell& r = implicit_[grid_.index(i, j)];
      if (r.mass == 0.0) continue;
      const double m_gas = gas_mass_density(i, j) * grid_.area(i, j);
      const GasProperties::At th = props_->thermo((*g.T)(i, j));
      const double cv_gas = th.cp / th.gamma;
      r.drag = 1.0 / (1.0 + dt * r.drag * (1.0 / m_gas + 1.0 / r.mass));
      r.heat = 1.0 / (1.0 + dt * r.heat * (1.0 / (m_gas * cv_gas) + 1.0 / r.heat_capacity));
    }
  }
}

void GasParticleCoupling::share_implicit_factors(int j1) {
  // A parcel at the cut reads the neighbour's factors too.
  Field2D& drag_factor = slab_->drag_factor;
  Field2D& heat_factor = slab_->heat_factor;
  for (int j = 0; j < j1; ++j) {
    for (int i = 0; i < grid_.nx(); ++i) {
      drag_factor(i, j) = implicit_[grid_.index(i, j)].drag;
      heat_factor(i, j) = implicit_[grid_.index(i, j)].heat;
    }
  }
  Field2D* const factors[] = {&drag_factor, &heat_factor};
  fill_ghosts(grid_, slab(), factors, 0, j1);
  const int ng = grid_.ghosts();
  for (int j = 0; j < j1; ++j) {
    for (int k = 1; k <= ng; ++k) {
      for (const int i : {-k, grid_.nx() - 1 + k}) {
        implicit_[grid_.index(i, j)].drag = drag_factor(i, j);
        implicit_[grid_.index(i, j)].heat = heat_factor(i, j);
      }
    }
  }
}

void GasParticleCoupling::scale_by_implicit_factors(const ParcelSystem& ps, std::size_t active,
                                                    double* K, double* H) const {
  const std::size_t n = active;
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    if (ps.is_rank_copy(k)) continue;  // its owner's (a rank copy's stencil may leave the slab)
    const DepositStencil& st = stencils_[k];
    double drag_factor = 0.0, heat_factor = 0.0;
    for (int m = 0; m < st.count; ++m) {
      const int i = st.i[static_cast<std::size_t>(m)], j = st.j[static_cast<std::size_t>(m)];
      const double f = st.fraction[static_cast<std::size_t>(m)];
      const ImplicitExchangeCell& r = implicit_[grid_.index(i, j)];
      drag_factor += f * r.drag;
      heat_factor += f * r.heat;
    }
    if (K != nullptr) K[k] *= drag_factor;
    if (H != nullptr) H[k] *= heat_factor;
  }
}

}  // namespace dustlift
