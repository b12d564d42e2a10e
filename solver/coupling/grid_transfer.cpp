#include "solver/coupling/grid_transfer.hpp"

#include <algorithm>
#include <cmath>

namespace dustlift {
namespace {

/// Index i of the centre at or left of s, with fraction t in [0, 1] towards centre i+1,
/// allowing the ghost centres -1 and n.
void bracket_centres(const Axis& a, double s, int& i, double& t) {
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

}  // namespace

InterpolationStencil interpolation_stencil(const Grid2D& g, double x, double y,
                                           InterpolationRule rule) {
  InterpolationStencil st;
  double s = 0.0, t = 0.0;
  bracket_centres(g.x(), x, st.i, s);
  bracket_centres(g.y(), y, st.j, t);
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

DepositStencil deposit_stencil(const Grid2D& g, double x, double y, double w) {
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
