#pragma once
// The output folder of a run (or sweep): a fresh run gets a fresh folder, so no file of an
// earlier run (stale .vtr, figures, series rows) can be mistaken for one of this run.
#include <string>

namespace dustlift {

enum class FolderUse {
  Fresh,      ///< must not exist or be empty
  Overwrite,  ///< --overwrite: an earlier dustlift output folder is emptied first
  Continue,   ///< a restart continuing in the folder of its checkpoint: kept as it is
};

/// Checks (before anything is written) that `dir` may be used so; SceneError naming the
/// folder otherwise: not empty without --overwrite; --overwrite on a folder that holds no
/// dustlift output (no run.log, scene.resolved.toml or summary.csv), which is never emptied.
void check_output_folder(const std::string& dir, FolderUse use);

/// Creates the folder (emptying it for Overwrite) and proves it is writable.
void prepare_output_folder(const std::string& dir, FolderUse use);

/// Whether `a` and `b` name the same folder (both may be missing: compared as absolute paths).
bool same_folder(const std::string& a, const std::string& b);

}  // namespace dustlift
