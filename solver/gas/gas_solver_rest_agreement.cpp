// A slab's skipping of resting cells decided as on the whole grid (RestAgreement): the
// references are the whole grid's corner cells, and per row the resting ends and the sources
// are the whole grid's, agreed by two element-wise minima over the slabs per step.
#include <limits>
#include <utility>

#include "solver/gas/gas_solver_impl.hpp"

namespace dustlift {

namespace {

constexpr double kNone = std::numeric_limits<double>::infinity();  // the minimum's identity

}  // namespace

/// Outside any parallel region (collective), in a stage that computes its ranges: the whole
/// grid's references (its cells (0, ny-1) and (columns-1, ny-1), from the slabs holding them),
/// this slab's scan at them, then per row the whole grid's resting ends and per interior row
/// its sources. The prefix resting at the left reference ends in the first slab whose own
/// scan stops before its last cell (a later slab's scan starts at most ng cells before its
/// first and so runs at least as far, each slab being wider than ng): the minimum over the
/// slabs whose scan stops there, and the last slab's. The suffix mirrors it (a maximum, sent
/// negated), as RestingParcels::agree_over_slabs does for the parcels' first resting column.
void GasSolver::Impl::agree_rest_rows() {
  const RestAgreement& a = rest_agreement;
  const int first = a.first_column;
  const bool first_slab = first == 0, last_slab = first + nx == a.whole_columns;
  double references[2 * kRestReferenceValues];
  pack_rest_reference(rest_reference_of(at(0, ny - 1)), first_slab, kNone, references);
  pack_rest_reference(rest_reference_of(at(nx - 1, ny - 1)), last_slab, kNone,
                      references + kRestReferenceValues);
  a.min_each(references);
  left_reference = unpack_rest_reference(references);
  right_reference = unpack_rest_reference(references + kRestReferenceValues);
#pragma omp parallel if (threaded)
  scan_rest_rows();
  const auto rows = static_cast<std::size_t>(ny + 2 * ng), interior = static_cast<std::size_t>(ny);
  agreed_.resize(2 * rows + 2 * interior);
  double* to = agreed_.data();
  double* from = to + rows;  // negated
  double* source_first = from + rows;
  double* source_last = source_first + interior;  // negated
  for (std::size_t k = 0; k < rows; ++k) {
    const bool prefix_stops = rest_to[k] < first + nx - 1;
    const bool suffix_stops = rest_from[k] > first;
    to[k] = prefix_stops || last_slab ? rest_to[k] : kNone;
    from[k] = suffix_stops || first_slab ? -rest_from[k] : kNone;
  }
  for (std::size_t k = 0; k < interior; ++k) {
    const SourceExtent& s = source_rows[k];
    source_first[k] = s.last >= 0 ? s.first : kNone;
    source_last[k] = s.last >= 0 ? -s.last : kNone;
  }
  a.min_each(agreed_);
  for (std::size_t k = 0; k < rows; ++k) {
    rest_to[k] = static_cast<int>(to[k]);
    rest_from[k] = static_cast<int>(-from[k]);
  }
  for (std::size_t k = 0; k < interior; ++k) {
    source_rows[k] = source_first[k] == kNone ? SourceExtent{a.whole_columns, -1}
                                              : SourceExtent{static_cast<int>(source_first[k]),
                                                             static_cast<int>(-source_last[k])};
  }
}

void GasSolver::set_rest_agreement(RestAgreement agreement) {
  Impl& m = *impl_;
  // Exact skipping needs no agreement: a stencil resting at any one state changes no bit, and
  // the slabs' edge updates (GhostFiller::changed_beyond) cover what reaches across a cut.
  if (!agreement.min_each || !(m.config.rest_tolerance > 0.0) || !m.skip_resting)
    agreement = {0, m.nx, {}};  // the grid's own columns, no collective
  m.rest_agreement = std::move(agreement);
  m.state_written();
}

}  // namespace dustlift
