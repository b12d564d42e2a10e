#pragma once
#include <cstddef>

namespace dustlift {

/// Below this many parcels (or cells) a loop runs on one thread: a parallel region costs more
/// than the work (and on a shared machine, threads waiting for a busy core cost far more).
/// Results do not depend on it (every parcel or cell gathers its own sums).
inline constexpr std::size_t kParallelMinimum = 4096;

}  // namespace dustlift
