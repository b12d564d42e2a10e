#pragma once
// What the series observers carry in a checkpoint (group insitu/<key>/), so that a run
// continued from it writes the same series as a run that was never interrupted.
#include <string>

#include "insitu/series_table.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

/// Stores every column of `table` as <prefix><table name>/<column name>.
void save_table(const SeriesTable& table, Snapshot& s, const std::string& prefix);
/// Takes them back into `table` (same columns); SnapshotError naming the array otherwise.
void restore_table(SeriesTable& table, const Snapshot& s, const std::string& prefix);

/// "The last time this observer wrote" markers: NaN for none.
void save_time(double time, bool present, Snapshot& s, const std::string& name);
/// Returns whether a time was stored and sets `time`; SnapshotError when the array is missing.
bool restore_time(double& time, const Snapshot& s, const std::string& name);

}  // namespace dustlift
