#include "solver/app/sweep_summary.hpp"

#include <fmt/core.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>

namespace fs = std::filesystem;

namespace dustlift {
namespace {

std::vector<SeriesColumn> numeric_columns(const Scene& base, const std::vector<double>& stations) {
  std::vector<SeriesColumn> c{{"run_index", "1"},     {"exit_status", "1"}, {"wall_time", "s"},
                              {"steps", "1"},         {"end_time", "s"},    {"shock_x", "m"},
                              {"lifting_delay", "m"}, {"layer_top", "m"}};
  for (double x : stations) c.push_back({"h_at_x" + number_in_identifier(x), "m"});
  for (const SummaryCloudColumn& cloud : kSummaryCloudColumns)
    c.push_back({cloud.summary, cloud.unit});
  for (const BandConfig& band : base.output.bands) {
    for (const std::string& component : kSummaryForceColumns) {
      c.push_back({band.name + "_" + component + "_peak", "N"});
      c.push_back({band.name + "_" + component + "_peak_tau", "s"});
    }
  }
  return c;
}

/// A scene key as a column name numpy and pandas keep: "particles.contact.damping" ->
/// "particles_contact_damping".
std::string key_column(const std::string& key) {
  std::string name;
  for (char c : key) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

/// CSV field: quoted when it holds a comma, quote or newline (RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

SweepSummary::SweepSummary(const std::vector<SweepAxis>& axes, const Scene& base,
                           const std::vector<double>& stations)
    : numbers_("summary", numeric_columns(base, stations)) {
  for (const auto& a : axes) keys_.insert(keys_.end(), a.keys.begin(), a.keys.end());
  key_values_.resize(keys_.size());
}

void SweepSummary::add(const SweepRun& run, const RunOutcome& outcome, const RunResults& results,
                       std::size_t index) {
  runs_.push_back(run.folder);
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    std::string value;
    for (const auto& [key, v] : run.overrides)
      if (key == keys_[k]) value = v;
    key_values_[k].push_back(value);
  }
  const bool ok = outcome.exit_code == kExitSuccess;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto result = [&](double v) { return ok ? v : nan; };
  std::vector<double> row{static_cast<double>(index),
                          static_cast<double>(outcome.exit_code),
                          outcome.wall_seconds,
                          static_cast<double>(outcome.steps),
                          outcome.time,
                          result(results.shock_x),
                          result(results.lifting_delay),
                          result(results.layer_top)};
  for (double h : results.heights) row.push_back(result(h));
  for (std::size_t c = 0; c < kSummaryCloudColumns.size(); ++c)
    row.push_back(c < results.cloud.size() ? result(results.cloud[c]) : nan);
  for (const auto& band : results.peaks) {
    for (const ForcePeak& p : band) {
      row.push_back(result(p.value));
      row.push_back(result(p.tau));
    }
  }
  numbers_.append_row(row);
}

void SweepSummary::write(const std::string& dir) const {
  fs::create_directories(dir);
  const fs::path csv = fs::path(dir) / "summary.csv", tmp = fs::path(dir) / "summary.csv.tmp";
  {
    std::ofstream f(tmp);
    f << "run";
    for (const auto& k : keys_) f << "," << key_column(k);
    for (std::size_t c = 0; c < numbers_.columns().size(); ++c) f << "," << numbers_.header(c);
    f << "\n";
    for (std::size_t r = 0; r < runs_.size(); ++r) {
      f << csv_field(runs_[r]);
      for (const auto& values : key_values_) f << "," << csv_field(values[r]);
      for (std::size_t c = 0; c < numbers_.columns().size(); ++c)
        f << "," << fmt::format("{}", numbers_.column(c)[r]);
      f << "\n";
    }
  }
  fs::rename(tmp, csv);
  const std::string h5 = (fs::path(dir) / "summary.h5").string();
  write_series_h5(h5, numbers_);
  write_string_column_h5(h5, "summary", "run", runs_);
  for (std::size_t k = 0; k < keys_.size(); ++k)
    write_string_column_h5(h5, "summary", key_column(keys_[k]), key_values_[k]);
}

}  // namespace dustlift
