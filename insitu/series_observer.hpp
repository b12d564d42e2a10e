#pragma once
// What every series observer shares: one sink made from the first view it writes with, the
// time it last sampled (so on_finish right after an output adds no second row), and its tables
// and that time carried in checkpoints (group insitu/<key>/), so a continued run writes the
// same series as a run that was never interrupted.
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "insitu/series_table.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

class SeriesObserver : public Observer {
 public:
  SeriesObserver(const SeriesObserver&) = delete;  // keeps pointers to its own tables
  SeriesObserver& operator=(const SeriesObserver&) = delete;

  std::string state_key() const final { return key_; }
  /// The kept tables, the last sample's time (NaN: none yet), then save_more().
  void save_state(Snapshot& s, const std::string& prefix) const final;
  void restore_state(const Snapshot& s, const std::string& prefix) final;
  /// The files brought back to the checkpoint's rows (nothing when nothing was sampled).
  void on_resume(const StateView& view, const std::string& previous_output_dir) override;

 protected:
  /// `key`: the checkpoint group; `time_name`: the dataset of the last sample's time.
  explicit SeriesObserver(std::string key, std::string time_name = "last_time")
      : key_(std::move(key)), time_name_(std::move(time_name)) {}

  /// The tables carried in checkpoints, in the derived observer's constructor (they are its
  /// members, so they outlive nothing of the base's).
  void keep(std::initializer_list<SeriesTable*> tables) { tables_.assign(tables); }
  /// Whether the state at `time` has been sampled already.
  bool sampled_at(double time) const { return sampled_ && time == last_time_; }
  bool sampled() const { return sampled_; }
  void mark_sampled(double time) {
    sampled_ = true;
    last_time_ = time;
  }
  /// Writes the series through the run's sink (made at the first call).
  void write_series(const StateView& view);

  /// What write_series writes: by default every kept table.
  virtual void write_tables(const SeriesSink& sink);
  /// State beyond the tables and the time (filter sums, cadences).
  virtual void save_more(Snapshot&, const std::string& /*prefix*/) const {}
  virtual void restore_more(const Snapshot&, const std::string& /*prefix*/) {}

 private:
  std::string key_, time_name_;
  std::vector<SeriesTable*> tables_;
  std::unique_ptr<SeriesSink> sink_;
  bool sampled_ = false;
  double last_time_ = 0.0;
};

}  // namespace dustlift
