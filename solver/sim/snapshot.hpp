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

/// The array `name` of one of a snapshot's maps; SnapshotError when it is missing or, with
/// `expected_size` > 0, has another length.
template <class T>
const std::vector<T>& snapshot_array(const std::map<std::string, std::vector<T>>& m, const std::string& name,
                                     std::size_t expected_size = 0) {
  const auto it = m.find(name);
  if (it == m.end()) throw SnapshotError("missing array '" + name + "'");
  if (expected_size != 0 && it->second.size() != expected_size) {
    throw SnapshotError("array '" + name + "' has " + std::to_string(it->second.size()) + " values, expected " +
                        std::to_string(expected_size));
  }
  return it->second;
}

/// The text `name` of a snapshot; SnapshotError when it is missing.
inline const std::string& snapshot_text(const Snapshot& s, const std::string& name) {
  const auto it = s.text.find(name);
  if (it == s.text.end()) throw SnapshotError("missing text '" + name + "'");
  return it->second;
}

}  // namespace dustlift
