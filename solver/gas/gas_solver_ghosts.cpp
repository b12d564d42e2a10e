// GasSolver's ghost cells: each side's filler (its boundary condition, or one set in its
// place such as a neighbouring rank's) called in the order the corners need.
#include "solver/gas/boundary_fillers.hpp"
#include "solver/gas/gas_solver_impl.hpp"

namespace dustlift {

/// This grid's boundary conditions, an inflow imposing inflow[side] (see PhysicalBoundary).
void GasSolver::Impl::make_boundaries(std::array<std::vector<PrimitiveState>, 4> inflow) {
  for (GridSide side : kGridSides) {
    const std::size_t k = side_index(side);
    boundary[k] = make_boundary_filler(side, boundary_kind(config.boundary, side), grid, R,
                                       std::move(inflow[k]));
  }
  resolve_fillers();
}

/// The boundary conditions with their inflow states: as given, else the initial state next
/// to the boundary (e.g. the post-shock state).
void GasSolver::Impl::record_inflow_states() {
  const BoundaryConfig& b = config.boundary;
  auto record = [&](int n, auto cell) {
    std::vector<PrimitiveState> out(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k)
      out[static_cast<std::size_t>(k)] = b.inflow_given ? b.inflow : cell(k);
    return out;
  };
  make_boundaries({record(ny, [&](int j) { return state_at(0, j); }),
                   record(ny, [&](int j) { return state_at(nx - 1, j); }),
                   record(nx, [&](int i) { return state_at(i, 0); }),
                   record(nx, [&](int i) { return state_at(i, ny - 1); })});
  fill_ghosts();
}

void GasSolver::Impl::resolve_fillers() {
  collective = {};
  std::size_t n = 0;
  for (GridSide side : kGridSides) {
    const std::size_t k = side_index(side);
    filler[k] = replaced[k] != nullptr ? replaced[k] : boundary[k].get();
    local[k] = !filler[k]->collective();
    if (!local[k] && (n == 0 || collective[n - 1] != filler[k])) collective[n++] = filler[k];
  }
}

PrimitiveGhosts GasSolver::Impl::primitive_ghosts() {
  // The slabs that agree on their ranges need not send them (widen_active_ranges).
  const bool send = skip_resting && !agrees_over_slabs();
  return {{&rho, &u, &v, &p, &T}, send ? row_lo.data() : nullptr, send ? row_hi.data() : nullptr};
}

/// The ghosts of the sides filled from this grid's own cells, by every thread of a
/// parallel region (or outside one). The x-sides first: the y-sides' corners read them.
void GasSolver::Impl::fill_local_ghosts() {
  const PrimitiveGhosts ghosts = primitive_ghosts();
  for (GridSide side : {GridSide::Left, GridSide::Right}) {
    if (local[side_index(side)]) filler[side_index(side)]->fill(ghosts);
  }
#pragma omp barrier
  for (GridSide side : {GridSide::Bottom, GridSide::Top}) {
    if (local[side_index(side)]) filler[side_index(side)]->fill(ghosts);
  }
#pragma omp barrier
}

/// The collective fillers' ghosts (outside a parallel region, after the local ones).
void GasSolver::Impl::fill_collective_ghosts() {
  for (GhostFiller* c : collective) {
    if (c != nullptr) c->fill(primitive_ghosts());
  }
}

/// Every ghost of the primitive fields, outside a parallel region.
void GasSolver::Impl::fill_ghosts() {
#pragma omp parallel if (threaded)
  fill_local_ghosts();
  fill_collective_ghosts();
}

void GasSolver::Impl::fill_porosity_ghosts() {
  for (GridSide side : kGridSides) {
    if (local[side_index(side)]) filler[side_index(side)]->fill_porosity(alpha);
  }
  for (GhostFiller* c : collective) {
    if (c != nullptr) c->fill_porosity(alpha);
  }
}

void GasSolver::set_ghost_filler(GridSide side, GhostFiller* filler) {
  if (filler != nullptr && filler->collective() && !is_x_side(side)) {
    throw std::invalid_argument(
        "GasSolver::set_ghost_filler: a collective filler serves an x-side");
  }
  Impl& m = *impl_;
  m.replaced[side_index(side)] = filler;
  m.resolve_fillers();
  m.state_written();
}

void GasSolver::set_fault_reporting(FaultReporting reporting) {
  impl_->fault_reporting = std::move(reporting);
  impl_->state_written();
}

}  // namespace dustlift
