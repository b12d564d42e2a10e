// GasSolver's step: three SSP-RK3 stages, each computing the face fluxes and updating the
// cells row by row in one pass (fluxes_and_update), over the cells that may change.
#include "solver/gas/gas_solver_impl.hpp"

namespace dustlift {

/// First interior row of thread t of `threads` in the fused flux-and-update loop.
int GasSolver::Impl::row_begin(int t, int threads) const {
  return static_cast<int>(static_cast<long long>(ny) * t / threads);
}

/// The face rows that read cell rows of two threads' ranges must be computed before any
/// of those rows changes: y-face rows j0-1 .. j0+1 (inviscid stencil rows jf-2 .. jf+1) and
/// x-face rows j0-1, j0 (viscous tangential derivatives, rows j-1 .. j+1) at each range
/// start j0. Each is given to the lowest thread whose boundary needs it; -1: computed by
/// the thread owning its rows, in its row loop.
void GasSolver::Impl::assign_boundary_faces(int threads) {
  std::fill(y_face_owner.begin(), y_face_owner.end(), -1);
  std::fill(x_face_owner.begin(), x_face_owner.end(), -1);
  for (int t = threads - 1; t >= 1; --t) {
    const int j0 = row_begin(t, threads);
    if (j0 <= 0 || j0 >= ny) continue;
    for (int k = std::max(j0 - 1, 0); k <= std::min(j0 + 1, ny); ++k)
      y_face_owner[static_cast<std::size_t>(k)] = t;
    for (int k = std::max(j0 - 1, 0); k <= std::min(j0, ny - 1); ++k)
      x_face_owner[static_cast<std::size_t>(k)] = t;
  }
  face_owners_for_threads = threads;
}

/// Fluxes and stage update fused row by row, so that a row's face fluxes are still in
/// cache when the row is updated: row r is updated as soon as every face that reads its
/// stage-input primitives is computed (y-face rows up to r+2, x-face rows up to r+1). Each
/// face is computed once, from the same inputs as in separate passes, so the result is
/// bitwise the same. Runs inside the stage's parallel region.
template <class Th>
void GasSolver::Impl::fluxes_and_update(const Th& th, double dt, double c_new) {
  const int threads = omp_get_num_threads(), tid = omp_get_thread_num();
#pragma omp single
  if (face_owners_for_threads != threads) assign_boundary_faces(threads);
  for (int k = 0; k <= ny; ++k)
    if (y_face_owner[static_cast<std::size_t>(k)] == tid) y_flux_row(th, k);
  for (int k = 0; k < ny; ++k)
    if (x_face_owner[static_cast<std::size_t>(k)] == tid) x_flux_row(th, k);
#pragma omp barrier
  const int j0 = row_begin(tid, threads), j1 = row_begin(tid + 1, threads);
  if (j0 >= j1) return;
  auto y_unowned = [&](int k) { return k <= ny && y_face_owner[static_cast<std::size_t>(k)] < 0; };
  auto x_unowned = [&](int k) { return k < ny && x_face_owner[static_cast<std::size_t>(k)] < 0; };
  for (int k = j0; k <= j0 + 1; ++k)
    if (y_unowned(k)) y_flux_row(th, k);
  if (x_unowned(j0)) x_flux_row(th, j0);
  for (int r = j0; r < j1; ++r) {
    if (y_unowned(r + 2)) y_flux_row(th, r + 2);
    if (x_unowned(r + 1)) x_flux_row(th, r + 1);
    update_row(th, r, dt, c_new);
  }
}

/// U = c_old U0 + c_new (U + dt L(U)) with c_old = 1 - c_new, written as
/// U0 + c_new (U - U0 + dt L) (stage_update.hpp), on the active cells of row j; then the
/// primitives of the cells whose state changed, and the checks.
template <class Th>
void GasSolver::Impl::update_row(const Th& th, int j, double dt, double c_new) {
  const std::size_t nfx = static_cast<std::size_t>(nx + 1);
  const std::size_t nfy = static_cast<std::size_t>(nx);
  const auto sx = static_cast<std::size_t>(stride);
  const int i0 = row_lo[static_cast<std::size_t>(j)], i1 = row_hi[static_cast<std::size_t>(j)];
  fault_i[static_cast<std::size_t>(j)] = -1;
  fault_kind[static_cast<std::size_t>(j)] = CellFault::None;
  if (i1 <= i0) return;
  const std::size_t c = at(i0, j);
  const std::size_t kx = static_cast<std::size_t>(j) * nfx + static_cast<std::size_t>(i0);
  const std::size_t ky = static_cast<std::size_t>(j) * nfy + static_cast<std::size_t>(i0);
  StageRow r{};
  for (int k = 0; k < Conserved::kCount; ++k) {
    r.U0[k] = U0[k].data() + c;
    r.U[k] = U[k].data() + c;
    r.source[k] = source[k].data() + c;
    r.fx[k] = fx[k].data() + kx;
    r.fy_below[k] = fy[k].data() + ky;
    r.fy_above[k] = fy[k].data() + ky + nfy;
  }
  r.fx_pressure = fx_pressure.data() + kx;
  r.fy_pressure_below = fy_pressure.data() + ky;
  r.fy_pressure_above = fy_pressure.data() + ky + nfy;
  r.alpha = alpha.data() + c;
  r.alpha_below = alpha.data() + c - sx;
  r.alpha_above = alpha.data() + c + sx;
  r.inv_dx = inv_dx.data() + static_cast<std::size_t>(i0 + ng);
  r.inv_dy = geo(inv_dy, j);
  r.gas_constant = R;
  r.gravity_x = config.gravity_x;
  r.gravity_y = config.gravity_y;
  r.prim = row_primitives(c);
  r.n = i1 - i0;
  save_step_start(j, i0, i1);
  cells_changed(j, i1);
  const int bad = stage_update_row(th, r, stage_scratch(), dt, c_new);
  if (bad >= 0) record_fault(j, i0 + bad);
}

/// Saves U0 = U for the cells of [i0, i1) not saved yet this step. A cell outside the hull
/// was not updated this step, so its U is still the step-start state.
void GasSolver::Impl::save_step_start(int j, int i0, int i1) {
  const auto k = static_cast<std::size_t>(j);
  int lo = saved_lo[k], hi = saved_hi[k];
  auto copy = [&](int a, int b) {
    if (b <= a) return;
    const std::size_t c = at(a, j), n = static_cast<std::size_t>(b - a);
    for (int q = 0; q < Conserved::kCount; ++q) std::copy_n(U[q].data() + c, n, U0[q].data() + c);
  };
  if (lo >= hi) {
    copy(i0, i1);
    lo = i0;
    hi = i1;
  } else {
    copy(std::min(lo, i0), lo);
    copy(hi, std::max(hi, i1));
    lo = std::min(lo, i0);
    hi = std::max(hi, i1);
  }
  saved_lo[k] = lo;
  saved_hi[k] = hi;
}

template <class Th>
void GasSolver::Impl::stage(const Th& th, double dt, double c_new) {
  // Collective fillers need the ghosts filled outside the stage's parallel region.
  const bool collective_fill = has_collective_fillers();
  if (collective_fill) fill_ghosts();
  // So are the slabs' agreements on what rests (collectives too).
  if (c_new == 1.0 && skip_resting && agrees_over_slabs()) agree_rest_rows();
#pragma omp parallel if (threaded)
  {
    if (!collective_fill) fill_local_ghosts();
    if (c_new == 1.0) {
      compute_active_ranges();
    } else {
      widen_active_ranges();
    }
    if (viscous) compute_transport(th);
    fluxes_and_update(th, dt, c_new);
  }
  for (int j = 0; j < ny; ++j)
    cell_updates += row_hi[static_cast<std::size_t>(j)] - row_lo[static_cast<std::size_t>(j)];
  throw_on_fault();
}

template <class Th>
void GasSolver::Impl::rk3_step(const Th& th, double dt) {
  if (externally_modified) {
    check_current_state();
    externally_modified = false;
  }
  ensure_scratch();
  fill_porosity_ghosts();
  find_source_rows();
  std::fill(saved_lo.begin(), saved_lo.end(), 0);
  std::fill(saved_hi.begin(), saved_hi.end(), 0);
  stage(th, dt, 1.0);
  stage(th, dt, 0.25);
  stage(th, dt, 2.0 / 3.0);
  fill_ghosts();
}

void GasSolver::step(double dt) {
  std::visit([&](const auto& th) { impl_->rk3_step(th, dt); }, impl_->thermo);
}

}  // namespace dustlift
