#include "insitu/series_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace dustlift {

bool is_identifier(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name.front()))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

std::string csv_unit_token(const std::string& unit) {
  const auto word = [](std::string part) {
    std::string out;
    for (char c : part) {
      if (c == ' ')
        out += '_';
      else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_')
        out += c;  // "^" and the like dropped
    }
    return out;
  };
  const auto slash = unit.find('/');
  if (slash == std::string::npos) return word(unit);
  const std::string numerator = word(unit.substr(0, slash)),
                    denominator = word(unit.substr(slash + 1));
  return numerator == "1" ? "per_" + denominator : numerator + "_per_" + denominator;
}

std::string number_in_identifier(double value) {
  std::string text = fmt::format("{:.9f}", value);
  text.erase(text.find_last_not_of('0') + 1);
  if (!text.empty() && text.back() == '.') text.pop_back();
  for (char& c : text) c = c == '.' ? 'p' : c == '-' ? 'm' : c;
  return text;
}

SeriesTable::SeriesTable(std::string name, std::vector<SeriesColumn> columns)
    : name_(std::move(name)), columns_(std::move(columns)), data_(columns_.size()) {
  if (columns_.empty()) throw std::invalid_argument("SeriesTable '" + name_ + "': no columns");
  if (!is_identifier(name_))
    throw std::invalid_argument("SeriesTable '" + name_ + "': not an identifier");
  for (const auto& c : columns_) {
    if (!is_identifier(c.name))
      throw std::invalid_argument("SeriesTable '" + name_ + "': column '" + c.name +
                                  "' is not an identifier");
  }
}

std::string SeriesTable::header(std::size_t k) const {
  return columns_.at(k).name + "_" + csv_unit_token(columns_.at(k).unit);
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
    throw std::invalid_argument(fmt::format("SeriesTable '{}': {} columns given, it has {}", name_,
                                            columns.size(), columns_.size()));
  for (const auto& c : columns) {
    if (c.size() != columns.front().size())
      throw std::invalid_argument(
          fmt::format("SeriesTable '{}': columns of different lengths", name_));
  }
  data_ = std::move(columns);
  csv_needs_rewrite_ = true;
}

SeriesSink::SeriesSink(std::string output_dir, SeriesFileInfo info)
    : series_dir_((std::filesystem::path(output_dir) / "series").string()),
      info_(std::move(info)) {}

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
  // Rows the last write put in both files and the table has not changed since.
  const std::size_t unchanged = table.csv_needs_rewrite() ? 0 : table.csv_rows_written();
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
  write_series_h5(h5_path(), table, &info_, unchanged);
}

}  // namespace dustlift
