#pragma once
// Scratch folders of tests: under the system temp directory, one per test process and name,
// removed when the process ends with every test passed. A failed test leaves them for a look
// (the failure messages name them), and DUSTLIFT_KEEP_TEST_DIRS=1 keeps them all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace dustlift::testing {

class ScratchFolders {
 public:
  ScratchFolders() = default;
  ScratchFolders(const ScratchFolders&) = delete;
  ScratchFolders& operator=(const ScratchFolders&) = delete;
  ~ScratchFolders() {
    // gtest's UnitTest is built before the first folder is asked for, so it outlives this.
    if (std::getenv("DUSTLIFT_KEEP_TEST_DIRS") != nullptr ||
        !::testing::UnitTest::GetInstance()->Passed())
      return;
    std::error_code ignored;
    for (const auto& p : paths_) std::filesystem::remove_all(p, ignored);
  }
  void add(const std::filesystem::path& p) { paths_.push_back(p); }

 private:
  std::vector<std::filesystem::path> paths_;
};

/// The folder temp/dustlift_<name>_<pid>, emptied (and created unless `create` is false: some
/// writers are checked to create their folder themselves).
inline std::filesystem::path scratch_dir(const std::string& name, bool create = true) {
  static ScratchFolders folders;
  auto p = std::filesystem::temp_directory_path() /
           ("dustlift_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  if (create) std::filesystem::create_directories(p);
  folders.add(p);
  return p;
}

}  // namespace dustlift::testing
