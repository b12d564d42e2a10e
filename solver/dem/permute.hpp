#pragma once
// Gathers of per-parcel arrays, shared by the parcel table's row operations.
#include <cstdint>
#include <vector>

#include "solver/dem/parcel_system.hpp"

namespace dustlift {

/// v[k] = old v[order[k]] for k < order.size() (a permutation or a selection), using
/// `scratch` (same element type) as buffer.
template <class T>
void permute(std::vector<T>& v, const std::vector<std::int32_t>& order, std::vector<T>& scratch) {
  const std::size_t n = order.size();
  scratch.resize(n);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) scratch[k] = v[order[k]];
  v.swap(scratch);
}

/// The same for `width` values per row: row k = old row order[k].
template <class T>
void permute_strided(std::vector<T>& v, const std::vector<std::int32_t>& order, std::size_t width,
                     std::vector<T>& scratch) {
  const std::size_t n = order.size();
  scratch.resize(n * width);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t w = 0; w < width; ++w)
      scratch[k * width + w] = v[static_cast<std::size_t>(order[k]) * width + w];
  }
  v.swap(scratch);
}

}  // namespace dustlift
