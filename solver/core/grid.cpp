#include "solver/core/grid.hpp"

#include "solver/core/derivatives.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dustlift {

double geometric_growth_ratio(double first, double length, std::size_t cells) {
  if (cells == 0 || first <= 0.0 || length <= 0.0) {
    throw std::invalid_argument("geometric stretching needs cells > 0, first > 0, length > 0");
  }
  const double n = static_cast<double>(cells);
  // One cell is the whole region: it may be narrower than the uniform cells (a half cell at
  // a wall puts the cell centres of a node-centred grid's points, docs/gas-solver.md).
  if (cells == 1) return 1.0;
  if (length < first * n) {
    throw std::invalid_argument("stretched region shorter than its cells at the uniform width");
  }
  if (std::abs(length - first * n) <= 1e-12 * length) return 1.0;
  // Solve first * (r^n - 1) / (r - 1) = length by bisection on r in (1, rmax].
  auto total = [&](double r) { return first * (std::pow(r, n) - 1.0) / (r - 1.0); };
  double lo = 1.0 + 1e-15, hi = 2.0;
  while (total(hi) < length) hi *= 2.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (total(mid) < length ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> build_axis_nodes(const AxisSpec& s) {
  if (!(s.end > s.start)) throw std::invalid_argument("axis end must be greater than start");
  std::vector<double> nodes;
  if (s.cell_size <= 0.0) {
    if (s.cells == 0) throw std::invalid_argument("axis needs at least one cell");
    if (s.cells > kMaxAxisCells) {
      throw std::invalid_argument("more than " + std::to_string(kMaxAxisCells) + " cells on one axis");
    }
    nodes.resize(s.cells + 1);
    for (std::size_t i = 0; i <= s.cells; ++i) {
      nodes[i] = s.start + (s.end - s.start) * static_cast<double>(i) / static_cast<double>(s.cells);
    }
    nodes.back() = s.end;
    return nodes;
  }
  const double us = s.uniform_start, ue = s.uniform_end, h = s.cell_size;
  if (!(us >= s.start && ue <= s.end && ue > us)) {
    throw std::invalid_argument("uniform region must lie inside [start, end] and have positive length");
  }
  const double n_uniform_real = (ue - us) / h;
  if (!(n_uniform_real + static_cast<double>(s.cells_below) + static_cast<double>(s.cells_above) <=
        static_cast<double>(kMaxAxisCells))) {
    throw std::invalid_argument("cell_size and cells_below/cells_above give more than " +
                                std::to_string(kMaxAxisCells) + " cells on one axis");
  }
  const auto n_uniform = static_cast<std::size_t>(std::llround(n_uniform_real));
  if (n_uniform == 0 || std::abs(n_uniform_real - static_cast<double>(n_uniform)) > 1e-6) {
    throw std::invalid_argument("uniform region length must be a whole number of cell_size");
  }
  if ((us > s.start) != (s.cells_below > 0)) {
    throw std::invalid_argument("cells_below must be > 0 exactly when uniform_start > start");
  }
  if ((ue < s.end) != (s.cells_above > 0)) {
    throw std::invalid_argument("cells_above must be > 0 exactly when uniform_end < end");
  }
  // Below: widths grow geometrically away from the uniform region (towards start).
  if (s.cells_below > 0) {
    const double r = geometric_growth_ratio(h, us - s.start, s.cells_below);
    std::vector<double> below(s.cells_below + 1);
    below[s.cells_below] = us;
    double w = h;
    for (std::size_t k = s.cells_below; k-- > 0;) {
      below[k] = below[k + 1] - w;
      w *= r;
    }
    below[0] = s.start;
    nodes.insert(nodes.end(), below.begin(), below.end() - 1);
  }
  for (std::size_t i = 0; i <= n_uniform; ++i) nodes.push_back(us + h * static_cast<double>(i));
  nodes.back() = ue;
  if (s.cells_above > 0) {
    const double r = geometric_growth_ratio(h, s.end - ue, s.cells_above);
    double w = h, x = ue;
    for (std::size_t k = 0; k < s.cells_above; ++k) {
      x += w;
      w *= r;
      nodes.push_back(x);
    }
    nodes.back() = s.end;
  }
  return nodes;
}

Axis::Axis(std::vector<double> interior_nodes, int ghosts)
    : n_(static_cast<int>(interior_nodes.size()) - 1), ng_(ghosts),
      interior_faces_(std::move(interior_nodes)) {
  if (n_ < 1) throw std::invalid_argument("axis needs at least one cell");
  if (ng_ < 0) throw std::invalid_argument("negative ghost count");
  const auto total = static_cast<std::size_t>(n_ + 2 * ng_);
  faces_.resize(total + 1);
  for (int i = 0; i <= n_; ++i) faces_[static_cast<std::size_t>(i + ng_)] = interior_faces_[static_cast<std::size_t>(i)];
  // Ghost cells mirror the interior widths about each end (the last interior width is
  // repeated when there are fewer interior cells than ghosts).
  for (int g = 1; g <= ng_; ++g) {
    const auto k = static_cast<std::size_t>(std::min(g, n_));
    const double w_left = interior_faces_[k] - interior_faces_[k - 1];
    const double w_right = interior_faces_[static_cast<std::size_t>(n_) - k + 1] -
                           interior_faces_[static_cast<std::size_t>(n_) - k];
    faces_[static_cast<std::size_t>(ng_ - g)] = faces_[static_cast<std::size_t>(ng_ - g + 1)] - w_left;
    faces_[static_cast<std::size_t>(ng_ + n_ + g)] = faces_[static_cast<std::size_t>(ng_ + n_ + g - 1)] + w_right;
  }
  finish();
}

Axis Axis::slice(int i0, int i1) const {
  if (i0 < 0 || i1 > n_ || i1 - i0 < 1) throw std::invalid_argument("axis slice: cells [i0, i1) must lie inside the axis");
  Axis a;
  a.n_ = i1 - i0;
  a.ng_ = ng_;
  // The slice's ghosts are this axis's cells beyond its ends (its own ghosts at a true end):
  // the same node values, so every width and centre of the slice has the bits of the whole.
  a.faces_.assign(faces_.begin() + i0, faces_.begin() + i1 + 2 * ng_ + 1);
  a.interior_faces_.assign(faces_.begin() + i0 + ng_, faces_.begin() + i1 + ng_ + 1);
  a.finish_from(*this, i0);
  return a;
}

void Axis::finish_from(const Axis& whole, int i0) {
  finish_geometry();
  // Derivative stencils are the whole axis's (one-sided only at its true ends), shifted.
  if (whole.n_ >= 3) {
    derivative_.resize(static_cast<std::size_t>(n_));
    for (int k = 0; k < n_; ++k) {
      DerivativeStencil d = whole.derivative_stencil(k + i0);
      d.first -= i0;
      derivative_[static_cast<std::size_t>(k)] = d;
    }
  }
  finish_buckets();
}

void Axis::finish() {
  finish_geometry();
  if (n_ >= 3) {
    derivative_.resize(static_cast<std::size_t>(n_));
    for (int k = 0; k < n_; ++k) {
      const int first = k == 0 ? 0 : (k == n_ - 1 ? n_ - 3 : k - 1);
      const ThreePointWeights w =
          derivative_weights(center(first), center(first + 1), center(first + 2), center(k));
      derivative_[static_cast<std::size_t>(k)] = {first, w.w0, w.w2};
    }
  }
  finish_buckets();
}

void Axis::finish_geometry() {
  const auto total = static_cast<std::size_t>(n_ + 2 * ng_);
  centers_.resize(total);
  widths_.resize(total);
  for (std::size_t k = 0; k < total; ++k) {
    centers_[k] = 0.5 * (faces_[k] + faces_[k + 1]);
    widths_[k] = faces_[k + 1] - faces_[k];
    if (!(widths_[k] > 0.0)) throw std::invalid_argument("axis nodes must increase strictly");
  }
}

void Axis::finish_buckets() {
  const double length = interior_faces_.back() - interior_faces_.front();
  const std::size_t buckets =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(length / min_width())), 1, 4 * static_cast<std::size_t>(n_));
  bucket_width_ = length / static_cast<double>(buckets);
  inverse_bucket_width_ = 1.0 / bucket_width_;
  bucket_first_.resize(buckets);
  last_bucket_ = static_cast<double>(buckets - 1);
  int cell = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    const double start = interior_faces_.front() + static_cast<double>(b) * bucket_width_;
    while (cell + 1 < n_ && interior_faces_[static_cast<std::size_t>(cell) + 1] <= start) ++cell;
    bucket_first_[b] = cell;
  }
}

double Axis::min_width() const {
  double w = width(0);
  for (int i = 1; i < n_; ++i) w = std::min(w, width(i));
  return w;
}

Grid2D::Grid2D(Axis x, Axis y) : x_(std::move(x)), y_(std::move(y)) {
  if (x_.ghosts() != y_.ghosts()) throw std::invalid_argument("axes need equal ghost counts");
}

Grid2D Grid2D::slice_x(int i0, int i1) const { return Grid2D(x_.slice(i0, i1), y_); }

Grid2D::Grid2D(const AxisSpec& x, const AxisSpec& y, int ghosts)
    : Grid2D(Axis(build_axis_nodes(x), ghosts), Axis(build_axis_nodes(y), ghosts)) {}

}  // namespace dustlift
