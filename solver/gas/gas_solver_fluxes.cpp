// GasSolver's face fluxes of one row of faces: the inviscid ones (flux_rows.hpp) and the
// viscous and heat fluxes (viscous_rows.hpp) over the faces of the cells a stage updates.
#include "solver/gas/gas_solver_impl.hpp"
#include "solver/gas/viscous_rows.hpp"

namespace dustlift {

/// The four stencil rows of a row of faces whose first face has cell c_m1 before it.
StencilRows GasSolver::Impl::stencil(const Field2D& q, std::size_t c_m1, std::size_t step) {
  const double* b = q.data() + c_m1;
  return {b - step, b, b + step, b + 2 * step};
}

FaceRowInput GasSolver::Impl::face_row_input(std::size_t c_m1, std::size_t step, int faces) const {
  return {stencil(rho, c_m1, step),
          stencil(u, c_m1, step),
          stencil(v, c_m1, step),
          stencil(p, c_m1, step),
          alpha.data() + c_m1,
          alpha.data() + c_m1 + step,
          faces};
}

/// Cells of grid row j (-1..ny) whose mu and lambda the viscous faces of the active rows
/// j-1..j+1 read: [lo, hi).
void GasSolver::Impl::transport_range(int j, int& lo, int& hi) const {
  lo = nx + 1;
  hi = -1;
  for (int r = std::max(j - 1, 0); r <= std::min(j + 1, ny - 1); ++r) {
    if (row_lo[static_cast<std::size_t>(r)] >= row_hi[static_cast<std::size_t>(r)]) continue;
    lo = std::min(lo, row_lo[static_cast<std::size_t>(r)] - 1);
    hi = std::max(hi, row_hi[static_cast<std::size_t>(r)] + 1);
  }
  lo = std::max(lo, -1);
  hi = std::min(hi, nx + 1);
}

template <class Th>
void GasSolver::Impl::compute_transport(const Th& th) {
#pragma omp for schedule(static)
  for (int j = -1; j <= ny; ++j) {
    int lo = 0, hi = 0;
    transport_range(j, lo, hi);
    if (hi <= lo) continue;
    const std::size_t c = at(lo, j);
    if (config.transport.model == TransportModel::GordonWilke) {
      air_table.apply(T.data() + c, mu.data() + c, lambda.data() + c, hi - lo);
      continue;
    }
    for (int i = lo; i < hi; ++i) {
      const std::size_t ci = at(i, j);
      const TransportProperties tp = transport_at(th, T.data()[ci]);
      mu.data()[ci] = tp.mu;
      lambda.data()[ci] = tp.lambda;
    }
  }
}

/// Subtracts the porosity-weighted viscous and heat fluxes of x-faces [f0, f1) of row j
/// (face f between cells f-1 and f).
void GasSolver::Impl::viscous_x_row(int j, int f0, int f1) {
  const std::size_t row =
      static_cast<std::size_t>(j) * static_cast<std::size_t>(nx + 1) + static_cast<std::size_t>(f0);
  const std::size_t hi = at(f0, j), lo = hi - 1, up = static_cast<std::size_t>(stride);
  const ViscousFaceCells c{
      u.data() + lo,      u.data() + hi,      v.data() + lo,      v.data() + hi,
      T.data() + lo,      T.data() + hi,      mu.data() + lo,     mu.data() + hi,
      lambda.data() + lo, lambda.data() + hi, alpha.data() + lo,  alpha.data() + hi,
      u.data() + lo - up, u.data() + lo + up, u.data() + hi - up, u.data() + hi + up,
      v.data() + lo - up, v.data() + lo + up, v.data() + hi - up, v.data() + hi + up};
  viscous_x_faces(c, inv_dxc.data() + static_cast<std::size_t>(f0 - 1 + ng), geo(inv_dy2, j),
                  fx[Conserved::kMomentumX].data() + row, fx[Conserved::kMomentumY].data() + row,
                  fx[Conserved::kEnergy].data() + row, f1 - f0);
}

/// Same for the y-faces [i0, i1) of face row jf (face (i, jf) between cells (i, jf-1), (i, jf)).
void GasSolver::Impl::viscous_y_row(int jf, int i0, int i1) {
  const std::size_t row =
      static_cast<std::size_t>(jf) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i0);
  const std::size_t hi = at(i0, jf), lo = hi - static_cast<std::size_t>(stride);
  const ViscousFaceCells c{
      u.data() + lo,      u.data() + hi,      v.data() + lo,     v.data() + hi,
      T.data() + lo,      T.data() + hi,      mu.data() + lo,    mu.data() + hi,
      lambda.data() + lo, lambda.data() + hi, alpha.data() + lo, alpha.data() + hi,
      u.data() + lo - 1,  u.data() + lo + 1,  u.data() + hi - 1, u.data() + hi + 1,
      v.data() + lo - 1,  v.data() + lo + 1,  v.data() + hi - 1, v.data() + hi + 1};
  viscous_y_faces(c, geo(inv_dyc, jf - 1), inv_dx2.data() + static_cast<std::size_t>(i0 + ng),
                  fy[Conserved::kMomentumX].data() + row, fy[Conserved::kMomentumY].data() + row,
                  fy[Conserved::kEnergy].data() + row, i1 - i0);
}

/// x-faces [row_lo, row_hi] of row j: those of its active cells (face f lies between
/// cells f-1 and f). Reads the primitives of row j (and of rows j-1, j+1 when viscous).
template <class Th>
void GasSolver::Impl::x_flux_row(const Th& th, int j) {
  const std::size_t nf = static_cast<std::size_t>(nx + 1);
  const int f0 = row_lo[static_cast<std::size_t>(j)], f1 = row_hi[static_cast<std::size_t>(j)] + 1;
  if (f1 - f0 < 2) return;
  const std::size_t row = static_cast<std::size_t>(j) * nf + static_cast<std::size_t>(f0);
  inviscid_flux_row(th, muscl, face_row_input(at(f0 - 1, j), 1, f1 - f0), thread_scratch(),
                    {fx[Conserved::kMass].data() + row, fx[Conserved::kMomentumX].data() + row,
                     fx[Conserved::kMomentumY].data() + row, fx[Conserved::kEnergy].data() + row,
                     fx_pressure.data() + row},
                    1.0, 0.0);
  if (viscous) viscous_x_row(j, f0, f1);
}

/// y-faces of face row jf under the active cells of the rows on either side.
void GasSolver::Impl::y_face_range(int jf, int& i0, int& i1) const {
  i0 = nx;
  i1 = 0;
  for (int r = jf - 1; r <= jf; ++r) {
    if (r < 0 || r >= ny) continue;
    const auto k = static_cast<std::size_t>(r);
    if (row_lo[k] >= row_hi[k]) continue;
    i0 = std::min(i0, row_lo[k]);
    i1 = std::max(i1, row_hi[k]);
  }
}

/// y-faces of face row jf (between cell rows jf-1 and jf). Reads the primitives of rows
/// jf-2 .. jf+1.
template <class Th>
void GasSolver::Impl::y_flux_row(const Th& th, int jf) {
  const auto step = static_cast<std::size_t>(stride);
  int i0 = 0, i1 = 0;
  y_face_range(jf, i0, i1);
  if (i1 <= i0) return;
  const std::size_t row =
      static_cast<std::size_t>(jf) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i0);
  inviscid_flux_row(th, muscl, face_row_input(at(i0, jf - 1), step, i1 - i0), thread_scratch(),
                    {fy[Conserved::kMass].data() + row, fy[Conserved::kMomentumX].data() + row,
                     fy[Conserved::kMomentumY].data() + row, fy[Conserved::kEnergy].data() + row,
                     fy_pressure.data() + row},
                    0.0, 1.0);
  if (viscous) viscous_y_row(jf, i0, i1);
}

template void GasSolver::Impl::compute_transport<CaloricallyPerfectGas>(
    const CaloricallyPerfectGas&);
template void GasSolver::Impl::compute_transport<ThermallyPerfectAir>(const ThermallyPerfectAir&);
template void GasSolver::Impl::x_flux_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&, int);
template void GasSolver::Impl::x_flux_row<ThermallyPerfectAir>(const ThermallyPerfectAir&, int);
template void GasSolver::Impl::y_flux_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&, int);
template void GasSolver::Impl::y_flux_row<ThermallyPerfectAir>(const ThermallyPerfectAir&, int);

}  // namespace dustlift
