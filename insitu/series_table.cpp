#include "insitu/series_table.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

namespace dustlift {

SeriesTable::SeriesTable(std::string name, std::vector<SeriesColumn> columns)
    : name_(std::move(name)), columns_(std::move(columns)), data_(columns_.size()) {
  if (columns_.empty()) throw std::invalid_argument("SeriesTable '" + name_ + "': no columns");
}

std::string SeriesTable::header(std::size_t k) const {
  return columns_.at(k).name + "_" + columns_.at(k).unit;
}

void SeriesTable::append_row(std::span<const double> row) {
  if (row.size() != columns_.size())
    throw std::invalid_argument(fmt::format("SeriesTable '{}': row has {} values, expected {}",
                                            name_, row.size(), columns_.size()));
  for (std::size_t k = 0; k < row.size(); ++k) data_[k].push_back(row[k]);
}

void SeriesTable::clear() {
  for (auto& c : data_) c.clear();
  csv_needs_rewrite_ = true;
}

void SeriesTable::assign(std::vector<std::vector<double>> columns) {
  if (columns.size() != columns_.size())
    throw std::invalid_argument(fmt::format("SeriesTable '{}': {} columns given, it has {}", name_, columns.size(),
                                            columns_.size()));
  for (const auto& c : columns) {
    if (c.size() != columns.front().size())
      throw std::invalid_argument(fmt::format("SeriesTable '{}': columns of different lengths", name_));
  }
  data_ = std::move(columns);
  csv_needs_rewrite_ = true;
}

SeriesSink::SeriesSink(std::string output_dir)
    : series_dir_((std::filesystem::path(output_dir) / "series").string()) {}

std::string SeriesSink::csv_path(const SeriesTable& table) const {
  return (std::filesystem::path(series_dir_) / (table.name() + ".csv")).string();
}

std::string SeriesSink::h5_path() const {
  return (std::filesystem::path(series_dir_) / "series.h5").string();
}

namespace {
void write_csv_rows(std::ofstream& out, const SeriesTable& table, std::size_t from) {
  for (std::size_t r = from; r < table.rows(); ++r) {
    for (std::size_t k = 0; k < table.columns().size(); ++k) {
      // Shortest representation that reads back to the same double (fmt's default).
      out << (k ? "," : "") << fmt::format("{}", table.column(k)[r]);
    }
    out << '\n';
  }
}
}  // namespace

void SeriesSink::write(SeriesTable& table) const {
  if (series_dir_.empty()) throw std::logic_error("SeriesSink: no output folder");
  std::filesystem::create_directories(series_dir_);
  const std::string path = csv_path(table);
  const bool rewrite = table.csv_needs_rewrite() || !std::filesystem::exists(path);
  std::ofstream out(path, rewrite ? std::ios::trunc : std::ios::app);
  if (!out) throw std::runtime_error("cannot write series file " + path);
  std::size_t from = table.csv_rows_written();
  if (rewrite) {
    for (std::size_t k = 0; k < table.columns().size(); ++k)
      out << (k ? "," : "") << table.header(k);
    out << '\n';
    from = 0;
  }
  write_csv_rows(out, table, from);
  out.flush();
  if (!out) throw std::runtime_error("error while writing series file " + path);
  table.mark_csv_written(table.rows());
  write_series_h5(h5_path(), table);
}

}  // namespace dustlift
