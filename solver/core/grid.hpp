#pragma once
// Rectilinear, optionally stretched 2-D grid with ghost layers.
// The paper's mesh (section 3.1): uniform 250 um cells in the main region,
// geometric stretching upstream (x < 0) and above y = 32 mm.
#include <cstddef>
#include <string>
#include <vector>

#include "solver/core/select.hpp"

namespace dustlift {

/// How one axis is built. Uniform spacing `cell_size` on [uniform_start, uniform_end];
/// `cells_below` cells stretched geometrically on [start, uniform_start] and
/// `cells_above` on [uniform_end, end], the first stretched cell as wide as `cell_size`.
/// Simplest use: start/end/cells with no stretching.
struct AxisSpec {
  double start = 0.0;          ///< m
  double end = 1.0;            ///< m
  std::size_t cells = 100;     ///< used when the axis is uniform (cell_size == 0)
  double cell_size = 0.0;      ///< m; > 0 selects the uniform-core + stretched-ends form
  double uniform_start = 0.0;  ///< m
  double uniform_end = 0.0;    ///< m
  std::size_t cells_below = 0;
  std::size_t cells_above = 0;
};

/// Most cells one axis may have. Far beyond any runnable 2-D grid (the paper's axes have
/// 1,900 and 160), it keeps a mistyped cell_size (say 250e-16 for 250e-6) from asking for
/// terabytes while the scene is parsed (found by fuzz/fuzz_scene_parser).
inline constexpr std::size_t kMaxAxisCells = 1'000'000;

/// Node coordinates of one axis (n_cells + 1 nodes), built from an AxisSpec.
/// Throws std::invalid_argument with a readable message on an impossible spec (including
/// more than kMaxAxisCells cells).
std::vector<double> build_axis_nodes(const AxisSpec& spec);

/// Growth ratio r of a geometric progression of `cells` cells whose first cell is `first`
/// and whose total length is `length` (r = 1 when length == cells * first, or when there is
/// one cell, which is then the whole region, whatever its width).
double geometric_growth_ratio(double first, double length, std::size_t cells);

/// What vector loops read of an Axis, as plain pointers and values (copied into the loop, so
/// the compiler need not reload them after every store): locate_bounded and the centres.
struct AxisView {
  const double* faces = nullptr;    ///< interior faces 0..n
  const double* centres = nullptr;  ///< centres[i] = centre of cell i, i in [-ng, n + ng)
  const int* bucket_first = nullptr;
  double start = 0.0, inverse_bucket_width = 1.0, last_bucket = 0.0;
  int n = 0;

  double centre(int i) const { return centres[i]; }
  /// Axis::locate without its open-ended scans: the bucket's first cell moved at most two cells
  /// up and one down. `exact` comes back false where that need not be the cell locate() gives
  /// (a NaN, or buckets wider than a cell); the caller then uses locate().
  int locate_bounded(double s, bool& exact) const {
    const double u = (s - start) * inverse_bucket_width;
    const double bucket = u >= 0.0 ? min_of(u, last_bucket) : 0.0;
    int i = bucket_first[static_cast<int>(bucket)];
    i += static_cast<int>((i + 1 < n) & (faces[i + 1] <= s));  // faces[n] exists
    i += static_cast<int>((i + 1 < n) & (faces[i + 1] <= s));
    i -= static_cast<int>((i > 0) & (faces[i] > s));
    // The cell whose faces hold s (the first or the last beyond the ends): where the scans of
    // locate() stop.
    exact = ((i == 0) | (faces[i] <= s)) & ((i + 1 >= n) | (faces[i + 1] > s));
    return i;
  }
};

/// One axis with ghost cells: interior cells 0..n-1, ghosts -ng..-1 and n..n+ng-1.
/// Ghost widths mirror the adjacent interior widths.
class Axis {
 public:
  Axis() = default;
  Axis(std::vector<double> interior_nodes, int ghosts);

  int cells() const { return n_; }
  int ghosts() const { return ng_; }
  /// Node coordinate of face i (i in [-ng, n+ng]); face i is the left face of cell i.
  double face(int i) const { return faces_[static_cast<std::size_t>(i + ng_)]; }
  double center(int i) const { return centers_[static_cast<std::size_t>(i + ng_)]; }
  double width(int i) const { return widths_[static_cast<std::size_t>(i + ng_)]; }
  double start() const { return face(0); }
  double end() const { return face(n_); }
  double min_width() const;
  /// Index of the interior cell holding coordinate s (clamped to [0, n-1]). Inline: every
  /// parcel locates itself several times per step.
  int locate(double s) const {
    // The bucket gives the first candidate cell; a short scan finds the one whose faces hold
    // s (the same cell as a binary search of the faces, without its dozen branches). The
    // scan corrects any start, so the bucket may come from a product, not a division.
    const double u = (s - interior_faces_.front()) * inverse_bucket_width_;
    if (!(u >= 0.0)) return 0;  // also NaN
    if (u >= static_cast<double>(bucket_first_.size())) return n_ - 1;
    int i = bucket_first_[static_cast<std::size_t>(u)];
    while (i + 1 < n_ && interior_faces_[static_cast<std::size_t>(i) + 1] <= s) ++i;
    while (i > 0 && interior_faces_[static_cast<std::size_t>(i)] > s) --i;
    return i;
  }
  const std::vector<double>& interior_faces() const { return interior_faces_; }
  AxisView view() const {
    return {interior_faces_.data(), centers_.data() + ng_, bucket_first_.data(), interior_faces_.front(),
            inverse_bucket_width_, last_bucket_, n_};
  }
  /// The three-point Lagrange derivative at interior centre k (one-sided at the ends), made
  /// once from the centres:
  ///   d f/ds = w0 (f[first] - f[first+1]) + w2 (f[first+2] - f[first+1])
  /// (derivatives.hpp; an axis of fewer than three cells has none).
  struct DerivativeStencil {
    int first = 0;
    double w0 = 0.0, w2 = 0.0;
  };
  const DerivativeStencil& derivative_stencil(int k) const {
    return derivative_[static_cast<std::size_t>(k)];
  }
  /// Cells [i0, i1) of this axis as an axis of their own (an MPI rank's slab): its ghost
  /// cells are this axis's neighbouring cells (or its ghosts at a true end), so every face,
  /// width and centre has the same bits, and its derivative stencils are this axis's, shifted
  /// (a stencil may then reach into the slice's ghosts).
  Axis slice(int i0, int i1) const;

 private:
  void finish();
  void finish_from(const Axis& whole, int i0);
  void finish_geometry();
  void finish_buckets();

  int n_ = 0;
  int ng_ = 0;
  std::vector<double> faces_, centers_, widths_, interior_faces_;
  std::vector<DerivativeStencil> derivative_;
  /// locate() in O(1): the axis cut into equal buckets no wider than its smallest cell (at
  /// most 4 n of them), each with the first cell it overlaps.
  double bucket_width_ = 1.0;
  double inverse_bucket_width_ = 1.0;
  std::vector<int> bucket_first_;
  double last_bucket_ = 0.0;  ///< bucket_first_.size() - 1
};

/// The 2-D grid: two axes and a cell indexing with ghosts (row-major, x fastest).
class Grid2D {
 public:
  Grid2D() = default;
  Grid2D(Axis x, Axis y);
  Grid2D(const AxisSpec& x, const AxisSpec& y, int ghosts);

  const Axis& x() const { return x_; }
  const Axis& y() const { return y_; }
  int nx() const { return x_.cells(); }
  int ny() const { return y_.cells(); }
  int ghosts() const { return x_.ghosts(); }
  /// Row stride and total size including ghosts.
  int stride() const { return nx() + 2 * ghosts(); }
  std::size_t size_with_ghosts() const {
    return static_cast<std::size_t>(stride()) * static_cast<std::size_t>(ny() + 2 * ghosts());
  }
  std::size_t interior_cells() const {
    return static_cast<std::size_t>(nx()) * static_cast<std::size_t>(ny());
  }
  /// Linear index of cell (i, j), ghosts allowed.
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>((j + ghosts()) * stride() + (i + ghosts()));
  }
  /// Columns [i0, i1) with every row: an MPI rank's x-slab (Axis::slice).
  Grid2D slice_x(int i0, int i1) const;
  /// Cell area (m^2), i.e. the cell volume per metre of depth.
  double area(int i, int j) const { return x_.width(i) * y_.width(j); }

 private:
  Axis x_, y_;
};

}  // namespace dustlift
