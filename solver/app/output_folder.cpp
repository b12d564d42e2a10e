#include "solver/app/output_folder.hpp"

#include <filesystem>
#include <fstream>

#include "solver/scene/table_reader.hpp"

namespace fs = std::filesystem;

namespace dustlift {
namespace {

bool holds_dustlift_output(const fs::path& dir) {
  for (const char* marker : {"run.log", "scene.resolved.toml", "summary.csv"}) {
    if (fs::exists(dir / marker)) return true;
  }
  return false;
}

std::string first_entries(const fs::path& dir) {
  std::string names;
  int n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (n++ == 3) {
      names += ", ...";
      break;
    }
    names += (names.empty() ? "" : ", ") + e.path().filename().string();
  }
  return names;
}

}  // namespace

bool same_folder(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
}

void check_output_folder(const std::string& dir, FolderUse use) {
  std::error_code ec;
  const fs::path p(dir);
  if (!fs::exists(p, ec) || use == FolderUse::Continue) return;
  if (!fs::is_directory(p, ec)) throw SceneError("output folder '" + dir + "': exists and is not a folder");
  if (fs::is_empty(p, ec)) return;
  if (use == FolderUse::Fresh) {
    throw SceneError("output folder '" + dir + "': not empty (" + first_entries(p) +
                     "); give a new folder, or --overwrite to replace an earlier run's output");
  }
  if (!holds_dustlift_output(p)) {
    throw SceneError("output folder '" + dir + "': --overwrite empties only a dustlift output folder, and this one has " +
                     "no run.log, scene.resolved.toml or summary.csv (" + first_entries(p) + ")");
  }
}

void prepare_output_folder(const std::string& dir, FolderUse use) {
  std::error_code ec;
  const fs::path p(dir);
  if (use == FolderUse::Overwrite && fs::is_directory(p, ec)) {
    for (const auto& e : fs::directory_iterator(p, ec)) fs::remove_all(e.path(), ec);
    if (ec) throw SceneError("output folder '" + dir + "': cannot empty it: " + ec.message());
  }
  fs::create_directories(p, ec);
  if (ec) throw SceneError("output folder '" + dir + "': cannot create: " + ec.message());
  const fs::path probe = p / ".dustlift-write-probe";
  {
    std::ofstream f(probe);
    if (!f || !(f << "x")) throw SceneError("output folder '" + dir + "': not writable");
  }
  fs::remove(probe, ec);
}

}  // namespace dustlift
