#include "insitu/series_state.hpp"

#include <cmath>
#include <limits>

namespace dustlift {

void save_table(const SeriesTable& table, Snapshot& s, const std::string& prefix) {
  for (std::size_t k = 0; k < table.columns().size(); ++k)
    s.f64[prefix + table.name() + "/" + table.columns()[k].name] = table.column(k);
}

void restore_table(SeriesTable& table, const Snapshot& s, const std::string& prefix) {
  std::vector<std::vector<double>> columns;
  for (const auto& c : table.columns()) {
    const std::string name = prefix + table.name() + "/" + c.name;
    columns.push_back(snapshot_array(s.f64, name));
    if (columns.back().size() != columns.front().size())
      throw SnapshotError("array '" + name + "' is not as long as the other columns of " +
                          table.name());
  }
  table.assign(std::move(columns));
}

void save_time(double time, bool present, Snapshot& s, const std::string& name) {
  s.f64[name] = {present ? time : std::numeric_limits<double>::quiet_NaN()};
}

bool restore_time(double& time, const Snapshot& s, const std::string& name) {
  const double t = snapshot_array(s.f64, name, 1)[0];
  if (std::isnan(t)) return false;
  time = t;
  return true;
}

}  // namespace dustlift
