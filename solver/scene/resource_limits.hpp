#pragma once
// What a scene will ask of the machine, estimated before anything is allocated, so that a
// grid of 10^12 cells or a layer of 10^11 parcels is bad input (exit 2, naming the key) and
// not std::bad_alloc halfway through building the run. The per-cell and per-parcel bytes
// were measured on this code (peak RSS of short runs, docs/reliability.md).
#include <cstdint>
#include <string>

namespace dustlift {

inline constexpr double kBytesPerCell = 700.0;     ///< gas fields, RK stages, fluxes, coupling, outputs
inline constexpr double kBytesPerParcel = 1700.0;  ///< SoA columns, neighbour list, cell sort, outputs
inline constexpr double kBytesBase = 50e6;         ///< program, libraries (VTK, HDF5)
/// Parcels carry int32 ids.
inline constexpr std::int64_t kMaxParcels = 2'000'000'000;

/// Physical memory of this machine, bytes (0 when unknown: no memory check).
double machine_memory_bytes();

/// Estimated peak memory of a run, bytes.
double estimated_run_bytes(double cells, double parcels);

/// "1.5 GB", "700 TB".
std::string format_bytes(double bytes);

/// Empty when the estimate fits in 90 % of the machine's memory; otherwise what it needs
/// against what the machine has ("needs about 700 TB of memory; this machine has 24 GB").
std::string memory_shortfall(double cells, double parcels);

}  // namespace dustlift
