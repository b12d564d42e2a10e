#pragma once
// Which cells a gas stage must update (GasSolver's exact skipping of resting regions).
// A cell whose whole stencil (MUSCL's two cells each way, the viscous corners) rests at one
// state, u = v = 0 with the same p and T, and that has no external source, gets L(U) = 0
// exactly from the well-balanced scheme (SLAU2 gives mass flux 0 and p~ = p to the last bit),
// so its update changes no bit: skipping it gives bitwise the same run. Ahead of a shock the
// gas is at rest and uniform; these ranges let a stage do only the work that changes something.
// With run.rest_tolerance > 0 "rests" means within that tolerance of the reference (the
// rounding noise ahead of the shock is skipped too; results change at that level).
#include <cmath>

namespace dustlift {

/// The resting state cells are compared with. With zero tolerances (the default) the
/// comparison is exact equality, so "uniform" means bitwise; run.rest_tolerance > 0 widens it
/// to |u|, |v| <= du, |p - p_ref| <= dp, |T - T_ref| <= dT (|x - y| <= 0 is x == y for finite
/// doubles, so one comparison serves both).
struct RestReference {
  bool valid = false;  ///< false: no cell counts as resting (the reference cell moves)
  double p = 0.0, T = 0.0;
  double du = 0.0, dp = 0.0, dT = 0.0;  ///< absolute tolerances (m/s, Pa, K)
};

/// The reference of a cell state (u, v, p, T, rho) under relative tolerance `tol`: dp = tol p,
/// dT = tol T, du = tol sqrt(p / rho) (the isothermal sound speed sets the velocity scale).
/// tol = 0: valid only for a cell exactly at rest.
inline RestReference rest_reference(double u, double v, double p, double T, double rho,
                                    double tol) {
  RestReference r;
  r.p = p;
  r.T = T;
  if (tol > 0.0) {
    r.dp = tol * p;
    r.dT = tol * T;
    r.du = tol * std::sqrt(p / rho);
  }
  r.valid = std::abs(u) <= r.du && std::abs(v) <= r.du;
  return r;
}

/// A reference as doubles (valid as 1 or 0), for a collective over the slabs of a grid, and
/// back: the slabs take the whole grid's reference from the slab that holds its cell.
inline constexpr int kRestReferenceValues = 6;
inline void pack_rest_reference(const RestReference& r, double* out) {
  const double values[kRestReferenceValues] = {r.valid ? 1.0 : 0.0, r.p, r.T, r.du, r.dp, r.dT};
  for (int q = 0; q < kRestReferenceValues; ++q) out[q] = values[q];
}
/// The same from every slab, where only the slab that `holds` the reference's cell gives it and
/// the others give `identity` (the identity of the collective that combines them: +inf for a
/// minimum, -inf for a maximum), so that the collective leaves every slab the holder's values.
inline void pack_rest_reference(const RestReference& r, bool holds, double identity, double* out) {
  pack_rest_reference(r, out);
  if (!holds)
    for (int q = 0; q < kRestReferenceValues; ++q) out[q] = identity;
}
inline RestReference unpack_rest_reference(const double* in) {
  RestReference r;
  r.valid = in[0] > 0.5;
  r.p = in[1];
  r.T = in[2];
  r.du = in[3];
  r.dp = in[4];
  r.dT = in[5];
  return r;
}

/// One grid row's u, v, p, T from its first cell on, `n` cells.
struct RowView {
  const double* u;
  const double* v;
  const double* p;
  const double* T;
  int n;
};

inline bool rests_at(const RowView& r, int i, const RestReference& ref) {
  return std::abs(r.u[i]) <= ref.du && std::abs(r.v[i]) <= ref.du &&
         std::abs(r.p[i] - ref.p) <= ref.dp && std::abs(r.T[i] - ref.T) <= ref.dT;
}

/// Number of leading cells of the row that rest at `ref`.
inline int resting_prefix(const RowView& r, const RestReference& ref) {
  if (!ref.valid) return 0;
  int i = 0;
  while (i < r.n && rests_at(r, i, ref)) ++i;
  return i;
}

/// Number of trailing cells of the row that rest at `ref`.
inline int resting_suffix(const RowView& r, const RestReference& ref) {
  if (!ref.valid) return 0;
  int k = 0;
  while (k < r.n && rests_at(r, r.n - 1 - k, ref)) ++k;
  return k;
}

/// First and last cell of an interior row (n cells) where any of the four source arrays is
/// non-zero; {n, -1} when none.
struct SourceExtent {
  int first = 0, last = -1;
};
inline SourceExtent source_extent(const double* const s[4], int n) {
  SourceExtent e{n, -1};
  for (int i = 0; i < n; ++i) {
    if (s[0][i] != 0.0 || s[1][i] != 0.0 || s[2][i] != 0.0 || s[3][i] != 0.0) {
      e.first = i < e.first ? i : e.first;
      e.last = i;
    }
  }
  return e;
}

/// Cells [lo, hi) of an interior row to update.
struct ActiveRange {
  int lo = 0, hi = 0;
};

/// For an interior row of n cells: `rest_to[w]` and `rest_from[w]` (w = 0..window-1, the rows
/// from `reach` below to `reach` above) are the last cell index resting at the left reference
/// and the first resting at the right one (cell indices as in the grid, ghosts negative or
/// >= n). A cell is skipped when every row of the window rests `reach` cells beyond it on
/// the same side and no cell from it outwards has a source.
inline ActiveRange active_range(const int* rest_to, const int* rest_from, int window,
                                SourceExtent src, int n) {
  const int reach = window / 2;
  int left_rest = rest_to[0], right_rest = rest_from[0];
  for (int w = 1; w < window; ++w) {
    left_rest = rest_to[w] < left_rest ? rest_to[w] : left_rest;
    right_rest = rest_from[w] > right_rest ? rest_from[w] : right_rest;
  }
  ActiveRange r;
  r.lo = left_rest - reach + 1;
  r.hi = right_rest + reach;
  r.lo = r.lo < 0 ? 0 : r.lo;
  r.hi = r.hi > n ? n : r.hi;
  // Cells with a source are updated wherever they are.
  if (src.last >= 0) {
    r.lo = src.first < r.lo ? src.first : r.lo;
    r.hi = src.last + 1 > r.hi ? src.last + 1 : r.hi;
  }
  if (r.lo > r.hi) r.lo = r.hi;
  return r;
}

}  // namespace dustlift
