#pragma once
// A ready-to-plot series: named columns with units, first column the abscissa.
// SeriesSink writes it to OUTDIR/series/<name>.csv (header "<name>_<unit token>,...", every
// header a valid identifier, e.g. u_m_per_s, so numpy and pandas keep it) and to the group
// /<name> of OUTDIR/series/series.h5 (one 1-D double dataset per column, attribute "units",
// the first column the dimension scale of the others). VTK-free and HDF5-free header.
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace dustlift {

struct SeriesColumn {
  std::string name;  ///< e.g. "time": letters, digits and _ (an identifier in every language)
  std::string unit;  ///< e.g. "s", "m/s"; "1" for dimensionless
};

/// The unit as it appears in a CSV header: letters, digits and _ only: "m/s" -> "m_per_s",
/// "1/s" -> "per_s", "kg/m^3" -> "kg_per_m3", "N m" -> "N_m", "1" -> "1".
std::string csv_unit_token(const std::string& unit);

/// Whether `name` may name a series or column: [A-Za-z_][A-Za-z0-9_]*.
bool is_identifier(const std::string& name);

/// A number as part of an identifier: fixed notation, '.' -> 'p', '-' -> 'm'
/// (0.025 -> "0p025", -0.01 -> "m0p01").
std::string number_in_identifier(double value);

class SeriesTable {
 public:
  SeriesTable(std::string name, std::vector<SeriesColumn> columns);

  const std::string& name() const { return name_; }
  const std::vector<SeriesColumn>& columns() const { return columns_; }
  std::size_t rows() const { return data_.empty() ? 0 : data_.front().size(); }
  const std::vector<double>& column(std::size_t k) const { return data_.at(k); }
  /// CSV header entry of column k: "<name>_<csv_unit_token(unit)>".
  std::string header(std::size_t k) const;

  /// Adds one row (one value per column; throws std::invalid_argument otherwise).
  void append_row(std::span<const double> row);
  /// Drops every row (for tables recomputed as a whole, e.g. band averages);
  /// the next SeriesSink::write rewrites the CSV instead of appending.
  void clear();
  /// Replaces every row by `columns` (one vector per column, equally long; a checkpoint's
  /// copy); the next SeriesSink::write rewrites the CSV. Throws std::invalid_argument when
  /// the shape does not fit.
  void assign(std::vector<std::vector<double>> columns);

  // Bookkeeping for SeriesSink: rows already in the CSV file.
  std::size_t csv_rows_written() const { return csv_rows_written_; }
  bool csv_needs_rewrite() const { return csv_needs_rewrite_; }
  void mark_csv_written(std::size_t rows) {
    csv_rows_written_ = rows;
    csv_needs_rewrite_ = false;
  }

 private:
  std::string name_;
  std::vector<SeriesColumn> columns_;
  std::vector<std::vector<double>> data_;
  std::size_t csv_rows_written_ = 0;
  bool csv_needs_rewrite_ = true;  // first write creates the file with its header
};

/// What series.h5 records about how it was made (root attributes).
struct SeriesFileInfo {
  std::string code_version, command_line;
  std::string scene;  ///< the resolved scene (TOML)
};

/// Writes tables of one run. Call write() at every output: the CSV and the table's group of
/// series.h5 get the rows added since the last call (both are rewritten after clear() or
/// assign()); series.h5 is opened, flushed and closed, so a killed run leaves both files
/// readable up to the last output.
class SeriesSink {
 public:
  SeriesSink() = default;  ///< no folder yet: write() throws until one is given
  explicit SeriesSink(std::string output_dir, SeriesFileInfo info = {});
  void write(SeriesTable& table) const;
  std::string csv_path(const SeriesTable& table) const;
  std::string h5_path() const;

 private:
  std::string series_dir_;
  SeriesFileInfo info_;
};

/// Brings the group /<table.name()> of an HDF5 file to the table's columns (creating the file
/// if missing or unreadable; a group with other columns is replaced whole) and, with `info`,
/// sets the root attributes code_version, command_line, scene and written_at (UTC, ISO 8601).
/// The table's first `unchanged_rows` rows are those this group already holds (rows appended
/// since the last call): only the rows after them are written. Safe to call repeatedly.
void write_series_h5(const std::string& path, const SeriesTable& table,
                     const SeriesFileInfo* info = nullptr, std::size_t unchanged_rows = 0);

/// Reads group /<name> back (column order and units from its attributes). Throws
/// std::runtime_error when the file or group is missing.
SeriesTable read_series_h5(const std::string& path, const std::string& name);

/// Writes a 1-D dataset of fixed-length strings /<group>/<name> into an HDF5 file (created
/// if missing; the group too), replacing a dataset of that name. For text columns next to a
/// series, e.g. the run names and override values of a sweep summary.
void write_string_column_h5(const std::string& path, const std::string& group,
                            const std::string& name, const std::vector<std::string>& values);

/// Reads such a dataset back. Throws std::runtime_error when it is missing.
std::vector<std::string> read_string_column_h5(const std::string& path, const std::string& group,
                                               const std::string& name);

}  // namespace dustlift
