#pragma once
// Validated reading of one TOML table: every key read is typed and range-checked,
// every key left unread is an error, and each value read is recorded into the
// resolved scene. Errors name the file, line and full dotted key (SceneError).
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <toml++/toml.h>

namespace dustlift {

/// Bad input: the message already names file, line and key.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true}; }
  bool contains(double v) const;
  std::string describe() const;
};

/// The whole text of an input file; SceneError naming it ("<path>: is a folder, not a
/// <kind>", "cannot open <kind>") otherwise.
std::string read_input_file(const std::string& path, const std::string& kind);

class TableReader {
 public:
  /// `table` may be null (section absent: all defaults). `out` receives the resolved values.
  TableReader(const toml::table* table, std::string prefix, std::string file, toml::table* out);

  bool has(std::string_view key) const;
  double number(std::string_view key, double fallback, Range range = {});
  double required_number(std::string_view key, Range range = {});
  std::optional<double> optional_number(std::string_view key, Range range = {});
  long long integer(std::string_view key, long long fallback, long long min, long long max);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, std::string fallback);
  /// A required file path, relative to the folder of the scene file unless absolute; the
  /// resolved scene records it absolute (it then reads back from any folder).
  std::string path(std::string_view key);
  /// A string restricted to `allowed` (the error lists them).
  std::string choice(std::string_view key, std::string fallback,
                     std::initializer_list<std::string_view> allowed);
  std::vector<double> number_list(std::string_view key, std::vector<double> fallback,
                                  Range range = {});
  /// A sub-table; `required` makes its absence an error.
  TableReader table(std::string_view key, bool required = false);
  /// Array of tables (e.g. [[insitu.bands]]).
  std::vector<TableReader> table_array(std::string_view key);

  /// Throws SceneError for the first key that was present but never read.
  void finish() const;

  /// An error about `key` of this table, with its source position.
  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  std::string full_key(std::string_view key) const;
  const std::string& file() const { return file_; }
  bool present() const { return table_ != nullptr; }

 private:
  const toml::node* node(std::string_view key) const;
  std::string where(const toml::node* n) const;
  void mark(std::string_view key);

  const toml::table* table_;
  std::string prefix_;
  std::string file_;
  toml::table* out_;
  std::vector<std::string> read_;
};

}  // namespace dustlift
