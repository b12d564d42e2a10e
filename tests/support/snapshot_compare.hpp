#pragma once
// Bitwise comparison of snapshot arrays and whole files for the checkpoint/restart tests.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/sim/snapshot.hpp"

namespace dustlift::testing {

/// Number of entries whose bytes differ (a length difference counts as more than all).
template <class T>
std::size_t differing(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size()) + 1;
  std::size_t n = 0;
  for (std::size_t k = 0; k < a.size(); ++k) n += std::memcmp(&a[k], &b[k], sizeof(T)) != 0;
  return n;
}

/// A whole file as bytes.
inline std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

/// Every array of two snapshots, bitwise; names the first that differs. `with_insitu` false
/// leaves out the observers' state (insitu/: series so far), e.g. when one run wrote a
/// final frame the other did not.
inline void expect_bitwise_equal(const Snapshot& a, const Snapshot& b, bool with_insitu = true) {
  const auto compared = [&](const std::string& name) { return with_insitu || name.rfind("insitu/", 0) != 0; };
  std::size_t arrays = 0;
  for (const auto& [name, v] : a.f64) {
    if (!compared(name)) continue;
    ++arrays;
    ASSERT_TRUE(b.f64.count(name)) << name;
    EXPECT_EQ(differing(v, b.f64.at(name)), 0u) << name;
  }
  for (const auto& [name, v] : b.f64) EXPECT_TRUE(!compared(name) || a.f64.count(name)) << name;
  for (const auto& [name, v] : a.i64) {
    if (compared(name)) {
      EXPECT_EQ(differing(v, b.i64.at(name)), 0u) << name;
    }
  }
  for (const auto& [name, v] : a.i32) EXPECT_EQ(differing(v, b.i32.at(name)), 0u) << name;
  for (const auto& [name, v] : a.i8) EXPECT_EQ(differing(v, b.i8.at(name)), 0u) << name;
  EXPECT_GT(arrays, 0u);
}

}  // namespace dustlift::testing
