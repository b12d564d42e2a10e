#include "solver/scene/table_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dustlift {

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (min_exclusive ? !(v > min) : !(v >= min)) return false;
  if (max_exclusive ? !(v < max) : !(v <= max)) return false;
  return true;
}

std::string Range::describe() const {
  std::ostringstream s;
  s.precision(10);
  const bool lo = std::isfinite(min), hi = std::isfinite(max);
  if (lo && hi) {
    s << "in " << (min_exclusive ? "(" : "[") << min << ", " << max << (max_exclusive ? ")" : "]");
  } else if (lo) {
    s << (min_exclusive ? "> " : ">= ") << min;
  } else if (hi) {
    s << (max_exclusive ? "< " : "<= ") << max;
  } else {
    s << "finite";
  }
  return s.str();
}

std::string read_input_file(const std::string& path, const std::string& kind) {
  // A folder opens as a stream on Linux and reads as empty: name it instead.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path + ": is a folder, not a " + kind);
  // A device or pipe (/dev/zero as a layer file) could be read forever.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw SceneError(path + ": is not a regular file, not a " + kind);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open " + kind);
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read " + kind);
  return buf.str();
}

TableReader::TableReader(const toml::table* table, std::string prefix, std::string file,
                         toml::table* out, ParseContext* context)
    : table_(table),
      prefix_(std::move(prefix)),
      file_(std::move(file)),
      out_(out),
      context_(context) {}

namespace {

/// Edits (insert, delete, replace) turning a into b.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// A value as TOML text (the shortest that reads back to the same double).
std::string toml_text(double v) {
  return fmt::format("{}", v);
}

std::string list_text(const std::vector<double>& v) {
  std::string text = "[";
  for (std::size_t k = 0; k < v.size(); ++k) text += (k ? ", " : "") + toml_text(v[k]);
  return text + "]";
}

std::string list_text(const std::vector<std::string>& v) {
  std::string text = "[";
  for (std::size_t k = 0; k < v.size(); ++k) text += (k ? ", \"" : "\"") + v[k] + "\"";
  return text + "]";
}

}  // namespace

void TableReader::expect_keys(std::initializer_list<std::string_view> keys) {
  expected_.assign(keys.begin(), keys.end());
  declared_ = true;
  if (context_ != nullptr)
    for (std::string_view k : keys) context_->keys.try_emplace(reference_key(full_key(k)));
  if (table_ == nullptr) return;
  for (const auto& [k, v] : *table_) {
    if (std::find(expected_.begin(), expected_.end(), k.str()) != expected_.end()) continue;
    std::string best;
    std::size_t best_distance = std::string::npos;
    for (const auto& e : expected_) {
      const std::size_t d = edit_distance(k.str(), e);
      if (d <= std::max<std::size_t>(2, e.size() / 3) && d < best_distance)
        best_distance = d, best = e;
    }
    throw SceneError(where(&v, full_key(k.str())) + ": key '" + full_key(k.str()) +
                     "': unknown key" +
                     (best.empty() ? "" : " (did you mean '" + full_key(best) + "'?)"));
  }
}

std::string reference_key(const std::string& full) {
  std::string out;
  for (std::size_t i = 0; i < full.size(); ++i) {
    if (full[i] ==
        '[') {  // an array of tables' entry: "output.bands[1].name" -> "output.bands.name"
      while (i < full.size() && full[i] != ']') ++i;
      continue;
    }
    out += full[i];
  }
  return out;
}

void TableReader::note_fact(std::string_view key, std::string kind, std::string fallback,
                            std::string range) {
  if (context_ == nullptr || read_depth_ != 1) return;
  context_->keys[reference_key(full_key(key))] =
      KeyFact{std::move(kind), std::move(fallback), std::move(range)};
}

std::string TableReader::full_key(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

std::string TableReader::where(const toml::node* n, const std::string& full) const {
  // Values from --set were parsed on their own: their source has no path.
  const toml::node* at = n != nullptr ? n : table_;
  if (at != nullptr && !at->source().path && context_ != nullptr) {
    const std::string key = n != nullptr ? full : prefix_;
    const std::pair<std::string, std::string>* best = nullptr;
    for (const auto& o : context_->overrides) {
      // The override's value, a part of it (an inline table), or a table made on its way.
      const bool covers = key == o.first || key.rfind(o.first + ".", 0) == 0 ||
                          key.rfind(o.first + "[", 0) == 0 || o.first.rfind(key + ".", 0) == 0;
      if (covers && (best == nullptr || o.first.size() > best->first.size())) best = &o;
    }
    if (best != nullptr) return "--set '" + best->second + "'";
  }
  std::ostringstream s;
  s << file_;
  if (n != nullptr && n->source().begin.line > 0) {
    s << ":" << n->source().begin.line;
  } else if (table_ != nullptr && table_->source().begin.line > 0) {
    s << ":" << table_->source().begin.line;
  }
  return s.str();
}

void TableReader::fail(std::string_view key, const std::string& what) const {
  throw SceneError(where(node(key), full_key(key)) + ": key '" + full_key(key) + "': " + what);
}

const toml::node* TableReader::node(std::string_view key) const {
  return table_ == nullptr ? nullptr : table_->get(key);
}

bool TableReader::has(std::string_view key) const {
  return node(key) != nullptr;
}

void TableReader::mark(std::string_view key) {
  if (declared_ && std::find(expected_.begin(), expected_.end(), key) == expected_.end()) {
    throw std::logic_error("TableReader: key '" + full_key(key) +
                           "' read but not declared in expect_keys");
  }
  if (std::find(read_.begin(), read_.end(), key) == read_.end()) read_.emplace_back(key);
}

bool TableReader::is_array(std::string_view key) const {
  const toml::node* n = node(key);
  return n != nullptr && n->is_array();
}

double TableReader::derived_number(std::string_view key, double derived, const std::string& from,
                                   Range range) {
  ReadScope scope(read_depth_);
  note_fact(key, "number", "from " + from, range.reference());
  if (auto v = optional_number(key, range)) return *v;
  note_derived(key, toml_text(derived), from);
  return derived;
}

bool TableReader::derived_boolean(std::string_view key, bool derived, const std::string& from) {
  ReadScope scope(read_depth_);
  note_fact(key, "boolean", "from " + from);
  if (has(key)) return boolean(key, derived);
  mark(key);
  note_derived(key, derived ? "true" : "false", from);
  return derived;
}

std::vector<double> TableReader::derived_number_list(std::string_view key,
                                                     const std::vector<double>& derived,
                                                     const std::string& from, Range range) {
  ReadScope scope(read_depth_);
  note_fact(key, "list of numbers", "from " + from, range.reference());
  if (has(key)) return number_list(key, derived, range);
  mark(key);
  std::string text = "[";
  for (std::size_t k = 0; k < derived.size(); ++k) text += (k ? ", " : "") + toml_text(derived[k]);
  note_derived(key, text + "]", from);
  return derived;
}

void TableReader::note_derived(std::string_view key, const std::string& toml,
                               const std::string& from) {
  if (context_ != nullptr) {
    // The kind stays the reader's (a scene that sets the key records it).
    context_->keys[reference_key(full_key(key))].fallback = "from " + from;
  }
  if (context_ != nullptr)
    context_->derived.push_back(full_key(key) + " = " + toml + "   # from " + from);
}

static const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

std::optional<double> TableReader::optional_number(std::string_view key, Range range) {
  ReadScope scope(read_depth_);
  note_fact(key, "number", "optional", range.reference());
  mark(key);
  const toml::node* n = node(key);
  if (n == nullptr) return std::nullopt;
  double v = 0.0;
  if (auto f = n->value_exact<double>()) {
    v = *f;
  } else if (auto i = n->value_exact<int64_t>()) {
    v = static_cast<double>(*i);
  } else {
    fail(key, std::string("expected a number, got ") + type_name(*n));
  }
  if (!range.contains(v)) {
    std::ostringstream s;
    s.precision(10);
    s << "value " << v << " out of range: must be " << range.describe();
    if (!range.bounds.empty()) s << ", i.e. " << range.bounds;
    fail(key, s.str());
  }
  if (out_ != nullptr) out_->insert_or_assign(key, v);
  return v;
}

double TableReader::number(std::string_view key, double fallback, Range range) {
  ReadScope scope(read_depth_);
  note_fact(key, "number", toml_text(fallback), range.reference());
  auto v = optional_number(key, range);
  if (!v) {
    if (out_ != nullptr) out_->insert_or_assign(key, fallback);
    return fallback;
  }
  return *v;
}

double TableReader::required_number(std::string_view key, Range range) {
  ReadScope scope(read_depth_);
  note_fact(key, "number", "required", range.reference());
  auto v = optional_number(key, range);
  if (!v) fail(key, "missing required number (" + range.reference() + ")");
  return *v;
}

long long TableReader::integer(std::string_view key, long long fallback, long long min,
                               long long max, std::string_view max_name) {
  ReadScope scope(read_depth_);
  note_fact(key, "integer", std::to_string(fallback),
            "in [" + std::to_string(min) + ", " +
                (!max_name.empty()                              ? std::string(max_name)
                 : max == std::numeric_limits<long long>::max() ? std::string("...")
                                                                : std::to_string(max)) +
                "]");
  mark(key);
  const toml::node* n = node(key);
  long long v = fallback;
  if (n != nullptr) {
    auto i = n->value_exact<int64_t>();
    if (!i) fail(key, std::string("expected an integer, got ") + type_name(*n));
    v = *i;
    if (v < min || v > max) {
      fail(key,
           "value " + std::to_string(v) + " out of range: must be in [" + std::to_string(min) +
               ", " + std::to_string(max) + "]" +
               (max_name.empty() ? std::string() : " (at most " + std::string(max_name) + ")"));
    }
  }
  if (out_ != nullptr) out_->insert_or_assign(key, static_cast<int64_t>(v));
  return v;
}

bool TableReader::boolean(std::string_view key, bool fallback) {
  ReadScope scope(read_depth_);
  note_fact(key, "boolean", fallback ? "true" : "false");
  mark(key);
  const toml::node* n = node(key);
  bool v = fallback;
  if (n != nullptr) {
    auto b = n->value_exact<bool>();
    if (!b) fail(key, std::string("expected true or false, got ") + type_name(*n));
    v = *b;
  }
  if (out_ != nullptr) out_->insert_or_assign(key, v);
  return v;
}

std::string TableReader::string(std::string_view key, std::string fallback) {
  ReadScope scope(read_depth_);
  note_fact(key, "string", "\"" + fallback + "\"");
  mark(key);
  const toml::node* n = node(key);
  std::string v = std::move(fallback);
  if (n != nullptr) {
    auto s = n->value_exact<std::string>();
    if (!s) fail(key, std::string("expected a string, got ") + type_name(*n));
    v = *s;
  }
  if (out_ != nullptr) out_->insert_or_assign(key, v);
  return v;
}

std::string TableReader::path(std::string_view key) {
  ReadScope scope(read_depth_);
  note_fact(key, "file", "required", "relative to the scene file");
  std::string given = string(key, "");
  if (given.empty()) fail(key, "missing required file path");
  const std::string resolved = resolve_path(given);
  if (out_ != nullptr) out_->insert_or_assign(key, resolved);
  return resolved;
}

std::string TableReader::resolve_path(const std::string& given) const {
  namespace fs = std::filesystem;
  fs::path p(given);
  if (p.is_relative()) p = fs::path(file_).parent_path() / p;
  return fs::absolute(p).lexically_normal().string();
}

std::vector<std::string> TableReader::existing_file_list(std::string_view key,
                                                         std::vector<std::string> fallback) {
  ReadScope scope(read_depth_);
  note_fact(key, "list of files", list_text(fallback), "relative to the scene file");
  namespace fs = std::filesystem;
  std::vector<std::string> v = string_list(key, std::move(fallback));
  for (auto& given : v) {
    const std::string resolved = resolve_path(given);
    std::error_code ec;
    if (!fs::is_regular_file(resolved, ec))
      fail(key, "no such file: " + given + " (looked for " + resolved + ")");
    given = resolved;
  }
  if (out_ != nullptr) {
    toml::array a;
    for (const auto& x : v) a.push_back(x);
    out_->insert_or_assign(key, std::move(a));
  }
  return v;
}

std::string TableReader::choice(std::string_view key, std::string fallback,
                                std::initializer_list<std::string_view> allowed) {
  return choice(key, std::move(fallback),
                std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

std::string TableReader::choice(std::string_view key, std::string fallback,
                                std::span<const std::string_view> allowed) {
  ReadScope scope(read_depth_);
  {
    std::string list;
    for (auto a : allowed)
      list += (list.empty() ? "" : ", ") + std::string("\"") + std::string(a) + "\"";
    note_fact(key, "one of", "\"" + fallback + "\"", list);
  }
  std::string v = string(key, std::move(fallback));
  if (std::find(allowed.begin(), allowed.end(), v) == allowed.end()) {
    std::string list;
    for (auto a : allowed)
      list += (list.empty() ? "" : ", ") + std::string("\"") + std::string(a) + "\"";
    fail(key, "\"" + v + "\" is not one of " + list);
  }
  return v;
}

std::vector<double> TableReader::number_list(std::string_view key, std::vector<double> fallback,
                                             Range range) {
  ReadScope scope(read_depth_);
  note_fact(key, "list of numbers", list_text(fallback), range.reference());
  mark(key);
  const toml::node* n = node(key);
  std::vector<double> v = std::move(fallback);
  if (n != nullptr) {
    const toml::array* arr = n->as_array();
    if (arr == nullptr)
      fail(key, std::string("expected an array of numbers, got ") + type_name(*n));
    v.clear();
    for (const auto& e : *arr) {
      double x = 0.0;
      if (auto f = e.value_exact<double>()) {
        x = *f;
      } else if (auto i = e.value_exact<int64_t>()) {
        x = static_cast<double>(*i);
      } else {
        fail(key, std::string("expected an array of numbers, found ") + type_name(e));
      }
      if (!range.contains(x)) {
        std::ostringstream s;
        s << "element " << x << " out of range: must be " << range.describe();
        fail(key, s.str());
      }
      v.push_back(x);
    }
  }
  if (out_ != nullptr) {
    toml::array a;
    for (double x : v) a.push_back(x);
    out_->insert_or_assign(key, std::move(a));
  }
  return v;
}

std::vector<std::string> TableReader::string_list(std::string_view key,
                                                  std::vector<std::string> fallback) {
  ReadScope scope(read_depth_);
  note_fact(key, "list of strings", list_text(fallback));
  mark(key);
  const toml::node* n = node(key);
  std::vector<std::string> v = std::move(fallback);
  if (n != nullptr) {
    const toml::array* arr = n->as_array();
    if (arr == nullptr)
      fail(key, std::string("expected an array of strings, got ") + type_name(*n));
    v.clear();
    for (const auto& e : *arr) {
      auto s = e.value_exact<std::string>();
      if (!s) fail(key, std::string("expected an array of strings, found ") + type_name(e));
      v.push_back(*s);
    }
  }
  if (out_ != nullptr) {
    toml::array a;
    for (const auto& x : v) a.push_back(x);
    out_->insert_or_assign(key, std::move(a));
  }
  return v;
}

TableReader TableReader::table(std::string_view key, bool required) {
  ReadScope scope(read_depth_);
  note_fact(key, "table", required ? "required" : "optional");
  mark(key);
  const toml::node* n = node(key);
  if (n == nullptr && required) fail(key, "missing required table");
  if (n != nullptr && !n->is_table())
    fail(key, std::string("expected a table, got ") + type_name(*n));
  toml::table* sub_out = nullptr;
  if (out_ != nullptr) {
    auto [it, inserted] = out_->insert(key, toml::table{});
    (void)inserted;
    sub_out = it->second.as_table();
  }
  return TableReader(n != nullptr ? n->as_table() : nullptr, full_key(key), file_, sub_out,
                     context_);
}

TableReader TableReader::lookahead(std::string_view key) const {
  const toml::node* n = node(key);
  return TableReader(n != nullptr ? n->as_table() : nullptr, full_key(key), file_, nullptr,
                     context_);
}

std::vector<TableReader> TableReader::table_array(std::string_view key) {
  ReadScope scope(read_depth_);
  note_fact(key, "array of tables", "none");
  mark(key);
  std::vector<TableReader> result;
  const toml::node* n = node(key);
  if (n == nullptr) return result;
  const toml::array* arr = n->as_array();
  if (arr == nullptr || !arr->is_array_of_tables())
    fail(key, "expected an array of tables ([[...]])");
  toml::array* out_arr = nullptr;
  if (out_ != nullptr) {
    auto [it, inserted] = out_->insert_or_assign(key, toml::array{});
    (void)inserted;
    out_arr = it->second.as_array();
  }
  for (std::size_t k = 0; k < arr->size(); ++k) {
    toml::table* sub_out = nullptr;
    if (out_arr != nullptr) {
      out_arr->push_back(toml::table{});
      sub_out = out_arr->back().as_table();
    }
    result.emplace_back((*arr)[k].as_table(), full_key(key) + "[" + std::to_string(k) + "]", file_,
                        sub_out, context_);
  }
  return result;
}

KeyFact* TableReader::recorded_fact(std::string_view key) {
  return context_ != nullptr ? &context_->keys[reference_key(full_key(key))] : nullptr;
}

void TableReader::finish() const {
  if (table_ == nullptr) return;
  for (const auto& [k, v] : *table_) {
    if (std::find(read_.begin(), read_.end(), k.str()) == read_.end()) {
      const bool known =
          declared_ && std::find(expected_.begin(), expected_.end(), k.str()) != expected_.end();
      throw SceneError(where(&v, full_key(k.str())) + ": key '" + full_key(k.str()) + "': " +
                       (known ? "not used with the other settings of this scene" : "unknown key"));
    }
  }
}

}  // namespace dustlift
