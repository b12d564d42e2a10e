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

/// The stencils of up to N points as columns (each quad's first cell as an index into any
/// Field2D of the grid), so that one field is interpolated at all of them in one vector loop
/// (gathers): the coupling samples nine fields at every parcel each step. Same bits as
/// InterpolationStencil::apply.
template <std::size_t N>
class InterpolationBatch {
 public:
  explicit InterpolationBatch(const Grid2D& g) : grid_(&g), row_(g.stride()) {}
  std::size_t size() const { return count_; }
  void clear() { count_ = 0; }
  void push(const InterpolationStencil& st) {
    first_[count_] = static_cast<std::int32_t>(grid_->index(st.i, st.j));
    w0_[count_] = st.weight[0];
    w1_[count_] = st.weight[1];
    w2_[count_] = st.weight[2];
    w3_[count_] = st.weight[3];
    ++count_;
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
  const Grid2D* grid_;
  std::int32_t row_;
  std::size_t count_ = 0;
  alignas(64) std::array<std::int32_t, N> first_{};
  alignas(64) std::array<double, N> w0_{}, w1_{}, w2_{}, w3_{};
};

enum class InterpolationRule { Triangle, Bilinear };

namespace detail {

/// Index i of the centre at or left of s, with fraction t in [0, 1] towards centre i+1,
/// allowing the ghost centres -1 and n.
inline void bracket_centres(const Axis& a, double s, int& i, double& t) {
  const int n = a.cells();
  const double lo = a.center(-1), hi = a.center(n);
  s = std::clamp(s, lo, hi);
  int k = a.locate(s);  // interior cell holding s (clamped)
  if (s < a.center(k)) --k;
  k = std::clamp(k, -1, n - 1);
  i = k;
  t = (s - a.center(k)) / (a.center(k + 1) - a.center(k));
  t = std::clamp(t, 0.0, 1.0);
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
  if (rule == InterpolationRule::Bilinear) {
    st.weight = {(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t};
  } else if (s >= t) {
    // Case 1: triangle (0,0)-(1,0)-(1,1); barycentric weights = sub-triangle area ratios.
    st.weight = {1.0 - s, s - t, 0.0, t};
  } else {
    // Case 2: triangle (0,0)-(0,1)-(1,1).
    st.weight = {1.0 - t, 0.0, t - s, s};
  }
  return st;
}

/// Up to four (cell, fraction) pairs of a deposit; fractions sum to one.
struct DepositStencil {
  int count = 0;
  std::array<int, 4> i{}, j{};
  std::array<double, 4> fraction{};
};

/// influence_width <= 0: the cell holding (x, y) takes everything (eq. 12 literally).
/// Otherwise a square of that side is split by area over the interior cells it overlaps
/// (clipped at the domain edges so nothing is lost). Inline, as the interpolation stencil.
inline DepositStencil deposit_stencil(const Grid2D& g, double x, double y, double w) {
  DepositStencil d;
  const Axis& ax = g.x();
  const Axis& ay = g.y();
  if (w <= 0.0) {
    d.count = 1;
    d.i[0] = ax.locate(x);
    d.j[0] = ay.locate(y);
    d.fraction[0] = 1.0;
    return d;
  }
  // Clip the square to the domain, then split it by overlap with at most 2 x 2 cells
  // (influence width must not exceed the smallest cell; checked by the scene).
  const double x0 = std::clamp(x - 0.5 * w, ax.start(), ax.end() - w);
  const double y0 = std::clamp(y - 0.5 * w, ay.start(), ay.end() - w);
  const int i0 = ax.locate(x0), j0 = ay.locate(y0);
  const double fx0 = std::min(1.0, (ax.face(i0 + 1) - x0) / w);
  const double fy0 = std::min(1.0, (ay.face(j0 + 1) - y0) / w);
  const double fx[2] = {fx0, 1.0 - fx0};
  const double fy[2] = {fy0, 1.0 - fy0};
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const double f = fx[a] * fy[b];
      if (f <= 0.0) continue;
      d.i[static_cast<std::size_t>(d.count)] = std::min(i0 + a, ax.cells() - 1);
      d.j[static_cast<std::size_t>(d.count)] = std::min(j0 + b, ay.cells() - 1);
      d.fraction[static_cast<std::size_t>(d.count)] = f;
      ++d.count;
    }
  }
  return d;
}

}  // namespace dustlift
