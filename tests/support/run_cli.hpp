#pragma once
// Runs the dustlift executable in tests and captures exit code and output.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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
inline CliResult run_cli(const std::string& args) {
  return run_command(std::string(DUSTLIFT_BINARY) + " " + args);
}

/// Starts the dustlift executable with `args` as a child process (its stdout and stderr into
/// the file `log`; in a process group of its own with `own_group`, as a batch system starts a
/// job) and returns its pid, for tests that signal a run from outside.
inline pid_t start_cli(const std::vector<std::string>& args, const std::string& log,
                       bool own_group = false) {
  const pid_t child = fork();
  if (child != 0) {
    if (own_group && child > 0) setpgid(child, child);  // either side may run first
    return child;
  }
  if (own_group) setpgid(0, 0);
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  dup2(fd, 1);
  dup2(fd, 2);
  std::vector<char*> argv{const_cast<char*>(DUSTLIFT_BINARY)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execv(DUSTLIFT_BINARY, argv.data());
  _exit(127);
}

/// A fresh empty folder under the system temp directory (scratch_dir.hpp: removed when the
/// test passes).
inline std::filesystem::path fresh_dir(const std::string& name) {
  return scratch_dir("test_" + name);
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

/// The bad-input contract (docs/reliability.md): exit code 2, one line "dustlift: error: ..."
/// naming `named`, and no output folder `out` left behind. `row` labels the failures.
inline void expect_bad_input(const CliResult& r, const std::string& named,
                             const std::filesystem::path& out, const std::string& row) {
  EXPECT_EQ(r.exit_code, 2) << row << "\n" << r.output;
  EXPECT_NE(r.output.find(named), std::string::npos)
      << row << ": message must name '" << named << "'\n"
      << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << row << ": one line\n"
                                                                   << r.output;
  EXPECT_EQ(r.output.rfind("dustlift: error: ", 0), 0u) << row << "\n" << r.output;
  EXPECT_FALSE(std::filesystem::exists(out))
      << row << ": a rejected run must leave no output folder";
}

}  // namespace dustlift::testing
