// GasSolver's skipping of resting cells (rest_ranges.hpp): the cells each stage updates,
// and the resting gas the coupling asks for.
#include "solver/gas/gas_solver_impl.hpp"

namespace dustlift {

/// Per row (ghost rows included) the cells at each end that rest at that end's reference
/// state, in the whole grid's columns. Every thread of a parallel region calls it.
void GasSolver::Impl::scan_rest_rows() {
  const int cells = nx + 2 * ng, first = rest_agreement.first_column;
#pragma omp single
  begin_suffix_scans(right_reference);
#pragma omp for schedule(static)
  for (int jr = -ng; jr < ny + ng; ++jr) {
    const std::size_t c = at(-ng, jr);
    const RowView row{u.data() + c, v.data() + c, p.data() + c, T.data() + c, cells};
    const auto k = static_cast<std::size_t>(jr + ng);
    rest_to[k] = first + resting_prefix(row, left_reference) - 1 - ng;
    rest_from[k] = first + cells - resting_suffix_of(jr, row, right_reference) - ng;
  }
}

namespace {
bool same_reference(const RestReference& a, const RestReference& b) {
  return a.valid == b.valid && a.p == b.p && a.T == b.T && a.du == b.du && a.dp == b.dp &&
         a.dT == b.dT;
}
}  // namespace

void GasSolver::Impl::begin_suffix_scans(const RestReference& ref) const {
  RestSuffixCache& cache = suffix_cache;
  if (cache.valid && same_reference(cache.reference, ref)) return;
  std::fill(cache.dirty_to.begin(), cache.dirty_to.end(), nx + 2 * ng);
  cache.reference = ref;
  cache.valid = true;
}

int GasSolver::Impl::resting_suffix_of(int jr, const RowView& row, const RestReference& ref) const {
  const auto k = static_cast<std::size_t>(jr + ng);
  int& dirty_to = suffix_cache.dirty_to[k];
  int& suffix = suffix_cache.suffix[k];
  const int cells = row.n, interior_end = cells - ng;
  int count = 0;
  if (!ref.valid) {
    count = 0;
  } else if (jr < 0 || jr >= ny || dirty_to >= interior_end) {
    // Ghost rows are written at every fill; a row changed up to its right ghosts is new.
    count = resting_suffix(row, ref);
  } else {
    // The right ghosts are written at every fill (boundary or halo): always looked at.
    int ghosts = 0;
    while (ghosts < ng && rests_at(row, cells - 1 - ghosts, ref)) ++ghosts;
    const int first_rested = cells - suffix;  // at the last scan
    // The left ghosts are written at every fill too.
    const int unchanged_from = std::max(dirty_to, ng);
    if (ghosts < ng) {
      count = ghosts;
    } else if (first_rested > interior_end) {
      // The last scan stopped in the ghosts: nothing is known of the interior.
      count = resting_suffix(row, ref);
    } else if (first_rested > unchanged_from) {
      // The cell before the resting run did not rest and has not changed: the same run.
      count = cells - first_rested;
    } else {
      // Cells from unchanged_from on rested and have not changed: walk on from there.
      int i = unchanged_from - 1;
      while (i >= 0 && rests_at(row, i, ref)) --i;
      count = cells - 1 - i;
    }
  }
  suffix = count;
  dirty_to = 0;
  return count;
}

/// The whole grid's cells [lo, hi) of interior row k to update, and this grid's part of them.
void GasSolver::Impl::set_row_range(std::size_t k, int lo, int hi) {
  whole_lo[k] = lo;
  whole_hi[k] = hi;
  const int first = rest_agreement.first_column;
  int own_lo = std::clamp(lo - first, 0, nx), own_hi = std::clamp(hi - first, 0, nx);
  if (own_lo > own_hi) own_lo = own_hi;
  row_lo[k] = own_lo;
  row_hi[k] = own_hi;
}

/// Per interior row the cells a stage must update (rest_ranges.hpp), from the resting ends
/// (on a slab agreed before the stage's parallel region: agree_rest_rows). Runs inside the
/// stage's parallel region after the ghosts were filled.
void GasSolver::Impl::compute_active_ranges() {
  if (!skip_resting) return;
  if (!agrees_over_slabs()) {
#pragma omp single
    {
      left_reference = rest_reference_of(at(0, ny - 1));
      right_reference = rest_reference_of(at(nx - 1, ny - 1));
    }
    scan_rest_rows();
  }
#pragma omp for schedule(static)
  for (int j = 0; j < ny; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const ActiveRange r = active_range(rest_to.data() + j, rest_from.data() + j, 2 * ng + 1,
                                       source_rows[k], rest_agreement.whole_columns);
    set_row_range(k, r.lo, r.hi);
  }
}

/// Where each row has sources this step (they are held constant over the step), in the whole
/// grid's columns.
void GasSolver::Impl::find_source_rows() {
  if (!skip_resting) return;
  const int first = rest_agreement.first_column;
  // Only where the sources' writer said they may be non-zero (the whole grid unless it did).
  const int rows_with = source_row_bound, columns_with = source_column_bound;
#pragma omp parallel for if (threaded) schedule(static)
  for (int j = 0; j < ny; ++j) {
    const std::size_t c = at(0, j);
    const double* const rows[Conserved::kCount] = {
        source[Conserved::kMass].data() + c, source[Conserved::kMomentumX].data() + c,
        source[Conserved::kMomentumY].data() + c, source[Conserved::kEnergy].data() + c};
    SourceExtent e = j < rows_with ? source_extent(rows, columns_with) : SourceExtent{};
    e = e.last >= 0 ? SourceExtent{e.first + first, e.last + first}
                    : SourceExtent{rest_agreement.whole_columns, -1};
    source_rows[static_cast<std::size_t>(j)] = e;
  }
}

/// Ranges of the next stage from this step's first: a stage changes only cells in its
/// ranges, so a cell further than the stencil reach (2 cells, 2 rows) from all of them
/// still has the resting stencil it had (exact; cheaper than scanning again). In the whole
/// grid's columns, so that every slab widens the ranges one grid would.
void GasSolver::Impl::widen_active_ranges() {
  if (!skip_resting) return;
  const int columns = rest_agreement.whole_columns;
#pragma omp single
  {
    widened_lo_ = whole_lo;
    widened_hi_ = whole_hi;
    for (int j = 0; j < ny; ++j) {
      int lo = columns, hi = 0;
      for (int r = std::max(j - ng, 0); r <= std::min(j + ng, ny - 1); ++r) {
        const auto k = static_cast<std::size_t>(r);
        if (widened_lo_[k] >= widened_hi_[k]) continue;
        lo = std::min(lo, widened_lo_[k] - ng);
        hi = std::max(hi, widened_hi_[k] + ng);
      }
      // Exact skipping on a slab (its own columns): the edge cells read ghosts copied from
      // another process's cells; where its previous stage updated those (within the stencil's
      // rows), they are updated too. Slabs that agree widen the same whole ranges instead.
      if (has_collective_fillers() && !agrees_over_slabs()) {
        const int r0 = std::max(j - ng, 0), r1 = std::min(j + ng, ny - 1) + 1;
        const auto changed = [&](GridSide side) {
          const std::size_t k = side_index(side);
          return !local[k] && filler[k]->changed_beyond(side, r0, r1);
        };
        if (changed(GridSide::Left)) {
          lo = std::min(lo, 0);
          hi = std::max(hi, std::min(ng, nx));
        }
        if (changed(GridSide::Right)) {
          lo = std::min(lo, std::max(nx - ng, 0));
          hi = std::max(hi, nx);
        }
      }
      lo = std::max(lo, 0);
      hi = std::min(hi, columns);
      set_row_range(static_cast<std::size_t>(j), lo < hi ? lo : 0, lo < hi ? hi : 0);
    }
  }
}

RestReference GasSolver::Impl::rest_reference_of(std::size_t c) const {
  return dustlift::rest_reference(u.data()[c], v.data()[c], p.data()[c], T.data()[c], rho.data()[c],
                                  config.rest_tolerance);
}

void GasSolver::add_column_work(std::vector<double>& per_column) const {
  const Impl& m = *impl_;
  if (per_column.size() != static_cast<std::size_t>(m.nx))
    throw std::invalid_argument("add_column_work: one entry per column");
  // A difference array over each row's range [lo, hi), then its running sum.
  std::vector<double> step(static_cast<std::size_t>(m.nx) + 1, 0.0);
  for (int j = 0; j < m.ny; ++j) {
    const auto k = static_cast<std::size_t>(j);
    if (m.row_lo[k] >= m.row_hi[k]) continue;
    step[static_cast<std::size_t>(m.row_lo[k])] += 1.0;
    step[static_cast<std::size_t>(m.row_hi[k])] -= 1.0;
  }
  double running = 0.0;
  for (int i = 0; i < m.nx; ++i) {
    running += step[static_cast<std::size_t>(i)];
    per_column[static_cast<std::size_t>(i)] += running;
  }
}

RestReference GasSolver::rest_reference() const {
  const Impl& m = *impl_;
  RestReference ref = m.rest_reference_of(m.at(m.nx - 1, m.ny - 1));
  // Under gravity no gas rests: the body force changes every cell's momentum.
  ref.valid = ref.valid && !m.config.has_gravity();
  return ref;
}

void GasSolver::resting_gas(RestingGas& out, const RestReference& ref) const {
  const Impl& m = *impl_;
  out.reference = ref;
  out.first_resting.resize(static_cast<std::size_t>(m.ny));
  const int cells = m.nx + 2 * m.ng;
  m.begin_suffix_scans(ref);
#pragma omp parallel for if (m.threaded) schedule(static)
  for (int j = 0; j < m.ny; ++j) {
    const std::size_t c = m.at(-m.ng, j);
    const RowView row{m.u.data() + c, m.v.data() + c, m.p.data() + c, m.T.data() + c, cells};
    out.first_resting[static_cast<std::size_t>(j)] =
        cells - m.resting_suffix_of(j, row, ref) - m.ng;
  }
}

}  // namespace dustlift
