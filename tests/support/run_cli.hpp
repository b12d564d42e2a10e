#pragma once
// Runs the dustlift executable in tests and captures exit code and output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include "tests/support/scratch_dir.hpp"

namespace dustlift::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs a shell command line; output is stdout and stderr together.
inline CliResult run_command(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  CliResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), pipe) != nullptr) r.output += buf.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// Runs the dustlift executable with `args`.
inline CliResult run_cli(const std::string& args) { return run_command(std::string(DUSTLIFT_BINARY) + " " + args); }

/// A fresh empty folder under the system temp directory (scratch_dir.hpp: removed when the
/// test passes).
inline std::filesystem::path fresh_dir(const std::string& name) { return scratch_dir("test_" + name); }

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

/// The bad-input contract (docs/reliability.md): exit code 2, one line "dustlift: error: ..."
/// naming `named`, and no output folder `out` left behind. `row` labels the failures.
inline void expect_bad_input(const CliResult& r, const std::string& named, const std::filesystem::path& out,
                             const std::string& row) {
  EXPECT_EQ(r.exit_code, 2) << row << "\n" << r.output;
  EXPECT_NE(r.output.find(named), std::string::npos) << row << ": message must name '" << named << "'\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << row << ": one line\n" << r.output;
  EXPECT_EQ(r.output.rfind("dustlift: error: ", 0), 0u) << row << "\n" << r.output;
  EXPECT_FALSE(std::filesystem::exists(out)) << row << ": a rejected run must leave no output folder";
}

}  // namespace dustlift::testing
