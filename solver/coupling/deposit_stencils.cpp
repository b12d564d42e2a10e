#include "solver/coupling/deposit_stencils.hpp"

#include "solver/coupling/coupling_slab.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {

bool DepositStencils::need_all(const ParcelSystem& parcels) const {
  return dem_steps_ < 0 || stencils_.size() != parcels.size() ||
         parcels.data_permutations() != permutations_;
}

void DepositStencils::update(const Grid2D& grid, const CouplingSlab* slab,
                             const ParcelSystem& parcels, std::size_t count) {
  const bool all = need_all(parcels);
  if (!all && dem_steps_ == parcels.steps()) return;  // no DEM step since: current
  const std::size_t n = parcels.size();
  // Parcels from `count` on did not move since their stencils were made (the caller's count
  // covers every parcel stepped since), and no re-sort moved them to other indices.
  const std::size_t end = all ? n : std::min(count, n);
  stencils_.resize(n);
  const double w = width_;
  constexpr std::size_t kBlock = 1024;
  const std::size_t blocks = (end + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) if (end >= kParallelMinimum)
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t k0 = b * kBlock;
    const std::size_t count = std::min(kBlock, end - k0);
    deposit_stencils(slab != nullptr ? *slab->whole : grid, parcels.x.data() + k0,
                     parcels.y.data() + k0, w, stencils_.data() + k0, count);
    // On a slab: the whole grid's columns as the slab's (the neighbour's cells fall outside
    // [0, nx) and are skipped by the deposits).
    if (slab != nullptr) {
      for (std::size_t k = k0; k < k0 + count; ++k) {
        for (int m = 0; m < stencils_[k].count; ++m)
          stencils_[k].i[static_cast<std::size_t>(m)] -= slab->first_column;
      }
    }
  }
  dem_steps_ = parcels.steps();
  permutations_ = parcels.data_permutations();
  planned_ = 0;  // the deposit plan was for the old stencils
}

void DepositStencils::plan(const Grid2D& grid, std::size_t count) {
  // A plan over more parcels serves too (the passes skip the columns they do not fill).
  if (planned_ >= count && planned_ > 0) return;
  scatter_.plan(stencils_, count, grid.nx(), kParallelMinimum);
  planned_ = count;
}

int DepositStencils::column_bound(const Grid2D& grid, double x) const {
  // A stencil's square [x0, x0 + w] with x0 >= x - w/2 clipped at the start (deposit_stencil,
  // grid_transfer.hpp).
  const double right = std::max(x + 0.5 * std::max(width_, 0.0), grid.x().start() + width_);
  return std::min(grid.nx() - 1, grid.x().locate(right) + 1);
}

std::size_t DepositStencils::parcels_reaching(const Grid2D& grid, const ParcelSystem& ps,
                                              int column) const {
  const std::size_t n = ps.size();
  // Near the right end a clipped square reaches further left than x - w/2: take all.
  if (column >= grid.nx() - 2) return n;
  const double half = 0.5 * std::max(width_, 0.0);
  const double face = grid.x().face(column + 1);
  const double* x = ps.x.data();
  std::size_t last = 0;
#pragma omp parallel for schedule(static) reduction(max : last) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    if (x[k] - half <= face) last = std::max(last, k + 1);
  }
  return last;
}

}  // namespace dustlift
