#pragma once
// The summary of a sweep: one row per run with its overrides, how it ended and its result
// quantities (run_summary.hpp), written as DIR/summary.csv and DIR/summary.h5
// (docs/output.md, "Sweeps").
#include <string>
#include <vector>

#include "insitu/series_table.hpp"
#include "solver/app/run_scene.hpp"
#include "solver/app/run_summary.hpp"
#include "solver/app/sweep.hpp"

namespace dustlift {

class SweepSummary {
 public:
  /// Columns from the sweep's keys, the stations and the bands of the base scene.
  SweepSummary(const std::vector<SweepAxis>& axes, const Scene& base,
               const std::vector<double>& stations);

  /// One run's row (`index`: its place in the sweep, the run_index column). A failed run
  /// (exit 3) records how far it got, its results stay NaN.
  void add(const SweepRun& run, const RunOutcome& outcome, const RunResults& results,
           std::size_t index);

  /// Rewrites DIR/summary.csv (header: run, the keys, then "<name>_<unit>" columns) and
  /// DIR/summary.h5 (group /summary: the numeric columns as a series with units, and
  /// string datasets "run" and one per key).
  void write(const std::string& dir) const;

 private:
  std::vector<std::string> keys_;
  std::vector<std::string> runs_;
  std::vector<std::vector<std::string>> key_values_;  ///< [key][run]
  SeriesTable numbers_;
};

}  // namespace dustlift
