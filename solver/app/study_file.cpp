// Study files: a sweep written down (cases/paper/studies/*.toml), read by `sweep --study`.
#include <cctype>
#include <filesystem>
#include <fmt/core.h>
#include <sstream>
#include <toml++/toml.h>

#include "solver/app/sweep.hpp"
#include "solver/scene/table_reader.hpp"

namespace dustlift {
namespace {

class StudyErrors {
 public:
  explicit StudyErrors(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void at(const toml::node* n, const std::string& key, const std::string& what) const {
    const long line = n != nullptr ? static_cast<long>(n->source().begin.line) : 0;
    throw SceneError(line > 0 ? fmt::format("{}:{}: key '{}': {}", file_, line, key, what)
                              : fmt::format("{}: key '{}': {}", file_, key, what));
  }

 private:
  std::string file_;
};

/// A string that --set reads back as that string without quotes (a plain word).
bool is_plain_word(const std::string& s) {
  if (s.empty() || s == "true" || s == "false" || s == "inf" || s == "nan") return false;
  if (!std::isalpha(static_cast<unsigned char>(s.front())) && s.front() != '_') return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  return true;
}

/// The value as --set text: numbers in their shortest exact form, plain words bare, other
/// strings quoted, arrays and inline tables as TOML.
std::string value_text(const toml::node& n) {
  if (auto f = n.value_exact<double>()) return fmt::format("{}", *f);
  if (auto i = n.value_exact<int64_t>()) return std::to_string(*i);
  if (auto b = n.value_exact<bool>()) return *b ? "true" : "false";
  if (auto s = n.value_exact<std::string>()) {
    if (is_plain_word(*s)) return *s;
  }
  std::ostringstream out;
  n.visit([&](const auto& v) { out << v; });
  return out.str();
}

}  // namespace

SweepDefinition read_study(const std::string& path) {
  const std::string text = read_input_file(path, "study file");
  toml::table doc;
  try {
    doc = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw SceneError(path + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " +
                     std::string(e.description()));
  }
  const StudyErrors error(path);
  SweepDefinition sweep;
  for (const auto& [k, node] : doc) {
    const std::string key(k.str());
    if (key == "scene") {
      const auto s = node.value_exact<std::string>();
      if (!s || s->empty()) error.at(&node, key, "expected the scene file (a string)");
      std::filesystem::path p(*s);
      if (p.is_relative()) p = std::filesystem::path(path).parent_path() / p;
      sweep.scene_path = p.lexically_normal().string();
    } else if (key == "lift_threshold") {
      const auto v = node.value<double>();
      if (!v || !(*v > 0.0)) error.at(&node, key, "expected a positive number (m)");
      sweep.lift_threshold = *v;
    } else if (key == "stations") {
      const toml::array* a = node.as_array();
      if (a == nullptr) error.at(&node, key, "expected an array of x positions (m)");
      for (const auto& e : *a) {
        const auto v = e.value<double>();
        if (!v) error.at(&e, key, "expected an array of numbers");
        sweep.stations.push_back(*v);
      }
    } else if (key == "set") {
      const toml::table* t = node.as_table();
      if (t == nullptr) error.at(&node, key, "expected a table of key = value overrides");
      for (const auto& [sk, sv] : *t) sweep.overrides.push_back(std::string(sk.str()) + "=" + value_text(sv));
    } else if (key == "vary") {
      const toml::array* a = node.as_array();
      if (a == nullptr || !a->is_array_of_tables()) error.at(&node, key, "expected [[vary]] tables of key = [values]");
      for (std::size_t n = 0; n < a->size(); ++n) {
        const toml::table& t = *(*a)[n].as_table();
        const std::string where = fmt::format("vary[{}]", n);
        SweepAxis axis;
        for (const auto& [vk, vv] : t) {
          const toml::array* values = vv.as_array();
          if (values == nullptr || values->empty()) error.at(&vv, where + "." + std::string(vk.str()), "expected a non-empty array of values");
          std::vector<std::string> texts;
          for (const auto& v : *values) texts.push_back(value_text(v));
          if (!axis.values.empty() && texts.size() != axis.size()) {
            error.at(&vv, where + "." + std::string(vk.str()),
                     fmt::format("{} values, but '{}' has {} (keys of one [[vary]] change together)", texts.size(),
                                 axis.keys.front(), axis.size()));
          }
          axis.keys.emplace_back(vk.str());
          axis.values.push_back(std::move(texts));
        }
        if (axis.keys.empty()) error.at(&(*a)[n], where, "an empty [[vary]] table");
        sweep.axes.push_back(std::move(axis));
      }
    } else {
      error.at(&node, key, "unknown key (a study has scene, set, [[vary]], stations, lift_threshold)");
    }
  }
  return sweep;
}

}  // namespace dustlift
