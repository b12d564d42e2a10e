#pragma once
// Everything a run needs to continue bitwise, as named typed arrays: the solver fills and
// reads it (Simulation::snapshot/restore), insitu/checkpoint.cpp stores it as HDF5
// datasets of the same names ("gas/conserved_0", "parcels/x", ...). Scalars are arrays of
// length 1. No HDF5 here. Layout and names: docs/reliability.md.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace dustlift {

struct Snapshot {
  std::map<std::string, std::vector<double>> f64;
  std::map<std::string, std::vector<std::int64_t>> i64;
  std::map<std::string, std::vector<std::int32_t>> i32;
  std::map<std::string, std::vector<std::int8_t>> i8;
  std::map<std::string, std::string> text;
};

/// A snapshot that does not fit the simulation it is restored into (missing array, wrong
/// length, inconsistent contact history). The message names the array.
class SnapshotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dustlift
