#pragma once
// Moving quantities between the Eulerian grid and parcels.
//  - Interpolation (eq. 16, Fig. 2): a parcel lies in the quad of the four nearest cell
//    centres; the quad is split along its diagonal and the parcel's triangle gives area
//    (barycentric) weights c1..c4 that sum to one (one of them is zero). Linear fields are
//    reproduced exactly. Ghost cells take part, so wall boundary conditions shape the values
//    interpolated in the half cell next to a wall.
//  - Deposition (eqs. 12-15): a parcel's contribution goes to the cell holding its centre
//    (the paper's rule), or is spread over the cells overlapped by a square "domain of
//    influence" of side `influence_width` centred on the parcel (Table 2). Both conserve
//    the deposited sum exactly.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/core/select.hpp"

namespace dustlift {

/// The value of a quad (eq. 16) from its four cell values and weights; a uniform quad gives
/// its value exactly (weighted sums of equal values can be off in the last bit, and a gas at
/// rest must look exactly at rest). The fused multiply-adds are written out so that the one
/// stencil and the batch below give the same bits whatever the compiler contracts.
inline double quad_value(double a, double b, double c, double d, double w0, double w1, double w2, double w3) {
  const double weighted = std::fma(w3, d, std::fma(w2, c, std::fma(w0, a, w1 * b)));
  return (a == b && a == c && a == d) ? a : weighted;
}

/// Four cells and weights (c1: (i, j), c2: (i+1, j), c3: (i, j+1), c4: (i+1, j+1)).
struct InterpolationStencil {
  int i = 0, j = 0;
  std::array<double, 4> weight{};
  /// The interpolated value (quad_value).
  double apply(const Field2D& f) const {
    return quad_value(f(i, j), f(i + 1, j), f(i, j + 1), f(i + 1, j + 1), weight[0], weight[1], weight[2], weight[3]);
  }
};

enum class InterpolationRule { Triangle, Bilinear };

namespace detail {

/// s clamped to the outermost centres (the ghost centres -1 and n).
inline double clamp_to_centres(const Axis& a, double s) { return clamp_of(s, a.center(-1), a.center(a.cells())); }

/// Index i of the centre at or left of s (clamped), with fraction t in [0, 1] towards centre
/// i+1, from the interior cell k holding s.
inline void bracket_from_cell(const Axis& a, double s, int k, int& i, double& t) {
  k -= static_cast<int>(s < a.center(k));
  k = clamp_of(k, -1, a.cells() - 1);
  i = k;
  t = (s - a.center(k)) / (a.center(k + 1) - a.center(k));
  t = clamp_of(t, 0.0, 1.0);
}

/// Index i of the centre at or left of s, with fraction t in [0, 1] towards centre i+1,
/// allowing the ghost centres -1 and n.
inline void bracket_centres(const Axis& a, double s, int& i, double& t) {
  s = clamp_to_centres(a, s);
  bracket_from_cell(a, s, a.locate(s), i, t);
}

/// The same for vector loops (AxisView::locate_bounded); false where it may differ. The
/// arithmetic of bracket_from_cell, written out on the view: GCC 12 did not vectorise the
/// callers' loop through a shared helper (the batch test checks both give the same bits).
inline bool bracket_centres_bounded(const AxisView& a, double s, int& i, double& t) {
  s = clamp_of(s, a.centre(-1), a.centre(a.n));
  bool exact = true;
  int k = a.locate_bounded(s, exact);
  k -= static_cast<int>(s < a.centre(k));
  k = clamp_of(k, -1, a.n - 1);
  i = k;
  t = (s - a.centre(k)) / (a.centre(k + 1) - a.centre(k));
  t = clamp_of(t, 0.0, 1.0);
  return exact;
}

/// The weights of a point at fractions (s, t) of its quad.
inline void interpolation_weights(double s, double t, bool bilinear, double& w0, double& w1, double& w2, double& w3) {
  // Triangle rule: case 1 (s >= t) the triangle (0,0)-(1,0)-(1,1), case 2 the triangle
  // (0,0)-(0,1)-(1,1); barycentric weights = sub-triangle area ratios. As selects, so that a
  // loop over points vectorises.
  const bool first = s >= t;
  w0 = bilinear ? (1 - s) * (1 - t) : (first ? 1.0 - s : 1.0 - t);
  w1 = bilinear ? s * (1 - t) : (first ? s - t : 0.0);
  w2 = bilinear ? (1 - s) * t : (first ? 0.0 : t - s);
  w3 = bilinear ? s * t : (first ? t : s);
}

}  // namespace detail

/// Stencil of point (x, y); points beyond the outermost interior centres use the ghost
/// layer (ghosts >= 1), points outside the grid are clamped to it. Inline: every parcel
/// makes one per step.
inline InterpolationStencil interpolation_stencil(const Grid2D& g, double x, double y,
                                                  InterpolationRule rule = InterpolationRule::Triangle) {
  InterpolationStencil st;
  double s = 0.0, t = 0.0;
  detail::bracket_centres(g.x(), x, st.i, s);
  detail::bracket_centres(g.y(), y, st.j, t);
  detail::interpolation_weights(s, t, rule == InterpolationRule::Bilinear, st.weight[0], st.weight[1], st.weight[2],
                                st.weight[3]);
  return st;
}

/// The stencils of up to N points as columns (each quad's first cell as an index into any
/// Field2D of the grid), so that one field is interpolated at all of them in one vector loop
/// (gathers): the coupling samples nine fields at every parcel each step. Same bits as
/// InterpolationStencil::apply.
template <std::size_t N>
class InterpolationBatch {
 public:
  explicit InterpolationBatch(const Grid2D& g) : grid_(&g), storage_(&g), row_(g.stride()) {}
  /// Stencils located on grid `g` (the whole grid) for fields stored on `storage`, a slab of
  /// it whose column 0 is g's column `first_column` (an MPI rank's, ghosts included).
  InterpolationBatch(const Grid2D& g, const Grid2D& storage, int first_column)
      : grid_(&g), storage_(&storage), row_(storage.stride()), shift_(first_column) {}
  std::size_t size() const { return count_; }
  void clear() { count_ = 0; }
  void push(const InterpolationStencil& st) { set(count_++, st); }
  /// Pushes the stencils of points (x[q], y[q]), q < n (at most N in all): the same stencils
  /// as interpolation_stencil, made in one vector loop.
  [[gnu::always_inline]] void push_points(const double* __restrict x, const double* __restrict y, std::size_t n, InterpolationRule rule) {
    const AxisView ax = grid_->x().view(), ay = grid_->y().view();
    const std::int32_t ng = grid_->ghosts(), row = row_, shift = shift_;
    const std::size_t q0 = count_;
    std::array<unsigned char, N> exact{};
    std::int32_t* __restrict first = first_.data();
    double* __restrict w0 = w0_.data();
    double* __restrict w1 = w1_.data();
    double* __restrict w2 = w2_.data();
    double* __restrict w3 = w3_.data();
    const bool bilinear = rule == InterpolationRule::Bilinear;
#pragma omp simd
    for (std::size_t q = 0; q < n; ++q) {
      int i = 0, j = 0;
      double s = 0.0, t = 0.0;
      const bool ex = detail::bracket_centres_bounded(ax, x[q], i, s);
      const bool ey = detail::bracket_centres_bounded(ay, y[q], j, t);
      exact[q] = static_cast<unsigned char>(ex & ey);
      first[q0 + q] = (j + ng) * row + (i - shift + ng);
      detail::interpolation_weights(s, t, bilinear, w0[q0 + q], w1[q0 + q], w2[q0 + q], w3[q0 + q]);
    }
    count_ += n;
    for (std::size_t q = 0; q < n; ++q) {
      if (exact[q] == 0) set(q0 + q, interpolation_stencil(*grid_, x[q], y[q], rule));
    }
  }
  /// out[q] = the value of f at point q, for every point pushed.
  void apply(const Field2D& f, double* __restrict out) const {
    const double* __restrict v = f.data();
    const std::int32_t row = row_;
#pragma omp simd
    for (std::size_t q = 0; q < count_; ++q) {
      const std::int32_t k = first_[q];
      out[q] = quad_value(v[k], v[k + 1], v[k + row], v[k + row + 1], w0_[q], w1_[q], w2_[q], w3_[q]);
    }
  }

 private:
  void set(std::size_t q, const InterpolationStencil& st) {
    first_[q] = static_cast<std::int32_t>(storage_->index(st.i - shift_, st.j));
    w0_[q] = st.weight[0];
    w1_[q] = st.weight[1];
    w2_[q] = st.weight[2];
    w3_[q] = st.weight[3];
  }
  const Grid2D* grid_;
  const Grid2D* storage_;
  std::int32_t row_;
  std::int32_t shift_ = 0;
  std::size_t count_ = 0;
  alignas(64) std::array<std::int32_t, N> first_{};
  alignas(64) std::array<double, N> w0_{}, w1_{}, w2_{}, w3_{};
};

/// Up to four (cell, fraction) pairs of a deposit; fractions sum to one.
struct DepositStencil {
  int count = 0;
  std::array<int, 4> i{}, j{};
  std::array<double, 4> fraction{};
};

namespace detail {

/// The deposit of a square whose lower-left corner (x0, y0) lies in cell (i0, j0) and which
/// covers the fractions fx0, fy0 of its side in that column and row (split over at most 2 x 2
/// cells, those with a positive share).
inline DepositStencil deposit_from_corner(const Grid2D& g, int i0, int j0, double fx0, double fy0) {
  DepositStencil d;
  const double fx[2] = {fx0, 1.0 - fx0};
  const double fy[2] = {fy0, 1.0 - fy0};
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const double f = fx[a] * fy[b];
      if (f <= 0.0) continue;
      d.i[static_cast<std::size_t>(d.count)] = std::min(i0 + a, g.x().cells() - 1);
      d.j[static_cast<std::size_t>(d.count)] = std::min(j0 + b, g.y().cells() - 1);
      d.fraction[static_cast<std::size_t>(d.count)] = f;
      ++d.count;
    }
  }
  return d;
}

/// The square's lower-left corner, clipped to the domain (so nothing is lost).
inline double square_start(double start, double end, double s, double w) { return clamp_of(s - 0.5 * w, start, end - w); }

/// The fraction of the square's side from s0 to the face ending its first cell.
inline double first_cell_fraction(double face_after, double s0, double w) { return min_of(1.0, (face_after - s0) / w); }

}  // namespace detail

/// influence_width <= 0: the cell holding (x, y) takes everything (eq. 12 literally).
/// Otherwise a square of that side is split by area over the interior cells it overlaps
/// (clipped at the domain edges so nothing is lost; influence width must not exceed the
/// smallest cell, checked by the scene). Inline, as the interpolation stencil.
inline DepositStencil deposit_stencil(const Grid2D& g, double x, double y, double w) {
  const Axis& ax = g.x();
  const Axis& ay = g.y();
  if (w <= 0.0) {
    DepositStencil d;
    d.count = 1;
    d.i[0] = ax.locate(x);
    d.j[0] = ay.locate(y);
    d.fraction[0] = 1.0;
    return d;
  }
  const double x0 = detail::square_start(ax.start(), ax.end(), x, w);
  const double y0 = detail::square_start(ay.start(), ay.end(), y, w);
  const int i0 = ax.locate(x0), j0 = ay.locate(y0);
  return detail::deposit_from_corner(g, i0, j0, detail::first_cell_fraction(ax.face(i0 + 1), x0, w),
                                     detail::first_cell_fraction(ay.face(j0 + 1), y0, w));
}

/// deposit_stencil of n points (x[k], y[k]) into out[k]: the same stencils, the squares
/// located in vector loops of up to 256 points.
inline void deposit_stencils(const Grid2D& g, const double* __restrict x, const double* __restrict y, double w,
                             DepositStencil* __restrict out, std::size_t n) {
  if (w <= 0.0) {
    for (std::size_t k = 0; k < n; ++k) out[k] = deposit_stencil(g, x[k], y[k], w);
    return;
  }
  const AxisView ax = g.x().view(), ay = g.y().view();
  const double x_start = g.x().start(), x_end = g.x().end(), y_start = g.y().start(), y_end = g.y().end();
  constexpr std::size_t kBlock = 256;
  alignas(64) std::array<int, kBlock> i0, j0;
  alignas(64) std::array<double, kBlock> fx0, fy0;
  alignas(64) std::array<unsigned char, kBlock> exact;
  for (std::size_t k0 = 0; k0 < n; k0 += kBlock) {
    const std::size_t m = std::min(kBlock, n - k0);
#pragma omp simd
    for (std::size_t q = 0; q < m; ++q) {
      const double xs = detail::square_start(x_start, x_end, x[k0 + q], w);
      const double ys = detail::square_start(y_start, y_end, y[k0 + q], w);
      bool ex = true, ey = true;
      const int i = ax.locate_bounded(xs, ex), j = ay.locate_bounded(ys, ey);
      i0[q] = i;
      j0[q] = j;
      exact[q] = static_cast<unsigned char>(ex & ey);
      fx0[q] = detail::first_cell_fraction(ax.faces[i + 1], xs, w);
      fy0[q] = detail::first_cell_fraction(ay.faces[j + 1], ys, w);
    }
    for (std::size_t q = 0; q < m; ++q) {
      const std::size_t k = k0 + q;
      out[k] = exact[q] != 0 ? detail::deposit_from_corner(g, i0[q], j0[q], fx0[q], fy0[q])
                             : deposit_stencil(g, x[k], y[k], w);
    }
  }
}

}  // namespace dustlift
