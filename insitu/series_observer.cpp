#include "insitu/series_observer.hpp"

#include "insitu/provenance_of.hpp"
#include "insitu/series_state.hpp"

namespace dustlift {

void SeriesObserver::save_state(Snapshot& s, const std::string& prefix) const {
  for (const SeriesTable* t : tables_) save_table(*t, s, prefix);
  save_time(last_time_, sampled_, s, prefix + time_name_);
  save_more(s, prefix);
}

void SeriesObserver::restore_state(const Snapshot& s, const std::string& prefix) {
  for (SeriesTable* t : tables_) restore_table(*t, s, prefix);
  sampled_ = restore_time(last_time_, s, prefix + time_name_);
  restore_more(s, prefix);
}

void SeriesObserver::on_resume(const StateView& view, const std::string&) {
  if (sampled_) write_series(view);
}

void SeriesObserver::write_series(const StateView& view) {
  if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
  write_tables(*sink_);
}

void SeriesObserver::write_tables(const SeriesSink& sink) {
  for (SeriesTable* t : tables_) sink.write(*t);
}

}  // namespace dustlift
