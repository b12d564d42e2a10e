#pragma once
// Validated reading of one TOML table: the keys a table knows are declared first (an unknown
// key, e.g. a typo of a required one, is reported as unknown before anything is read), every
// key read is typed and range-checked, every key left unread is an error, and each value read
// is recorded into the resolved scene; defaults derived from other keys are noted as comments
// instead, so the resolved scene derives them again. Errors name the file, line and full
// dotted key, or the --set override the value came from (SceneError).
#include <toml++/toml.h>

#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "solver/scene/key_fact.hpp"

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
  /// The bounds in words when they come from other keys (e.g. "in [grid.x.start,
  /// grid.x.end]"): what the key reference shows, since the numbers differ between scenes.
  std::string bounds;
  static Range positive() {
    return {0.0, std::numeric_limits<double>::infinity(), true, false, {}};
  }
  static Range non_negative() {
    return {0.0, std::numeric_limits<double>::infinity(), false, false, {}};
  }
  static Range closed(double lo, double hi) { return {lo, hi, false, false, {}}; }
  static Range open_closed(double lo, double hi) { return {lo, hi, true, false, {}}; }
  static Range open(double lo, double hi) { return {lo, hi, true, true, {}}; }
  /// This range with its bounds named by other keys (see `bounds`).
  Range named(std::string words) const {
    Range r = *this;
    r.bounds = std::move(words);
    return r;
  }
  bool contains(double v) const;
  /// The numeric range, e.g. "in [0, 0.15]" (error messages).
  std::string describe() const;
  /// What the key reference shows: `bounds` when given, else describe().
  std::string reference() const { return bounds.empty() ? describe() : bounds; }
};

/// The whole text of an input file; SceneError naming it ("<path>: is a folder, not a
/// <kind>", "cannot open <kind>") otherwise.
std::string read_input_file(const std::string& path, const std::string& kind);

/// A key as the scene-key reference names it: the entries of an array of tables without
/// their index ("output.bands[1].name" -> "output.bands.name").
std::string reference_key(const std::string& full);

/// What all readers of one scene share.
struct ParseContext {
  /// The --set overrides as (dotted key, "key=value"): a value that came from one is named by
  /// it in messages, not by a line of the file.
  std::vector<std::pair<std::string, std::string>> overrides;
  /// Derived defaults used, as "key = value  # from ..." (comments of the resolved scene).
  std::vector<std::string> derived;
  /// Every key declared or read, by dotted name (an array of tables' entries as
  /// "output.bands.name"): what the parser did with it.
  std::map<std::string, KeyFact> keys;
  /// run.allow_implausible: values outside the plausible range of their unit (a gas pressure
  /// below 1 kPa, a temperature below 100 K) are accepted (plausibility.hpp).
  bool allow_implausible = false;
};

class TableReader {
 public:
  /// `table` may be null (section absent: all defaults). `out` receives the resolved values.
  TableReader(const toml::table* table, std::string prefix, std::string file, toml::table* out,
              ParseContext* context = nullptr);

  /// Declares every key this table knows (values and sub-tables) and fails on the first key
  /// present that is not among them, naming the closest known key. Reading an undeclared key
  /// afterwards is a programming error (std::logic_error).
  void expect_keys(std::initializer_list<std::string_view> keys);

  bool has(std::string_view key) const;
  double number(std::string_view key, double fallback, Range range = {});
  double required_number(std::string_view key, Range range = {});
  std::optional<double> optional_number(std::string_view key, Range range = {});
  /// `max_name`, when given, names what sets `max` (e.g. "the layer's rows"): the key
  /// reference shows it instead of this scene's number.
  long long integer(std::string_view key, long long fallback, long long min, long long max,
                    std::string_view max_name = {});
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, std::string fallback);
  /// A required file path, relative to the folder of the scene file unless absolute; the
  /// resolved scene records it absolute (it then reads back from any folder).
  std::string path(std::string_view key);
  /// A list of paths to existing files, each resolved as path() does (recorded absolute); a
  /// missing file is an error naming the key.
  std::vector<std::string> existing_file_list(std::string_view key,
                                              std::vector<std::string> fallback);
  /// A string restricted to `allowed` (the error lists them).
  std::string choice(std::string_view key, std::string fallback,
                     std::initializer_list<std::string_view> allowed);
  std::string choice(std::string_view key, std::string fallback,
                     std::span<const std::string_view> allowed);
  std::vector<double> number_list(std::string_view key, std::vector<double> fallback,
                                  Range range = {});
  std::vector<std::string> string_list(std::string_view key, std::vector<std::string> fallback);
  bool is_array(std::string_view key) const;

  /// Keys whose default is derived from other keys: read and recorded like the others when
  /// present; when absent, `derived` is used and noted as a comment of the resolved scene
  /// (`from` says what it comes from), so the resolved scene run with other inputs derives it
  /// again instead of pinning this value.
  double derived_number(std::string_view key, double derived, const std::string& from,
                        Range range = {});
  bool derived_boolean(std::string_view key, bool derived, const std::string& from);
  std::vector<double> derived_number_list(std::string_view key, const std::vector<double>& derived,
                                          const std::string& from, Range range = {});
  /// Notes a derived default that is not a single value (e.g. a default array of tables),
  /// `toml` being its text.
  void note_derived(std::string_view key, const std::string& toml, const std::string& from);
  /// A sub-table; `required` makes its absence an error.
  TableReader table(std::string_view key, bool required = false);
  /// A look ahead into a sub-table read in full later (by table()): its reads record nothing
  /// in the resolved scene and mark nothing read here. A key that is not a table reads as an
  /// absent one (the later read reports it).
  TableReader lookahead(std::string_view key) const;
  /// Array of tables (e.g. [[insitu.bands]]).
  std::vector<TableReader> table_array(std::string_view key);

  /// What the key reference records for a key read already (null without a context), for
  /// what the read method cannot know: a key of two forms (true or a vector), or a list whose
  /// entries are restricted (its `range`: the reference's "allowed" column).
  KeyFact* recorded_fact(std::string_view key);

  /// Whether the scene confirmed implausible values (run.allow_implausible).
  bool implausible_allowed() const { return context_ != nullptr && context_->allow_implausible; }

  /// Throws SceneError for the first key that was present but never read.
  void finish() const;

  /// An error about `key` of this table, with its source position.
  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  std::string full_key(std::string_view key) const;
  const std::string& file() const { return file_; }
  bool present() const { return table_ != nullptr; }

 private:
  const toml::node* node(std::string_view key) const;
  /// `given` relative to the folder of the scene file unless absolute, made absolute.
  std::string resolve_path(const std::string& given) const;
  /// "file:line", or "--set 'a.b=v'" when the value (or the table holding it) came from one.
  std::string where(const toml::node* n, const std::string& full) const;
  void mark(std::string_view key);
  /// Notes what the outermost read of `key` did (nested reads, e.g. number() inside
  /// derived_number(), leave the outer one's fact).
  void note_fact(std::string_view key, std::string kind, std::string fallback,
                 std::string range = {});
  /// The read methods count their nesting here (note_fact records at depth 1 only).
  int read_depth_ = 0;
  struct ReadScope {
    int& depth;
    explicit ReadScope(int& d) : depth(++d) {}
    ~ReadScope() { --depth; }
  };

  const toml::table* table_;
  std::string prefix_;
  std::string file_;
  toml::table* out_;
  ParseContext* context_;
  std::vector<std::string> read_;
  std::vector<std::string> expected_;
  bool declared_ = false;
};

}  // namespace dustlift
