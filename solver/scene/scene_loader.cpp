#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "solver/scene/parse_sections.hpp"

namespace dustlift {
namespace {

/// Drops tables left empty (sections a scene did not use), so the resolved scene parses
/// back to the same scene.
void prune_empty_tables(toml::table& t) {
  std::vector<std::string> empty;
  for (auto& [k, v] : t) {
    if (auto* sub = v.as_table()) {
      prune_empty_tables(*sub);
      if (sub->empty()) empty.emplace_back(k.str());
    }
  }
  for (const auto& k : empty) t.erase(k);
}

/// Applies one `a.b.c=value` override to the parsed document; returns its key.
std::string apply_override(toml::table& doc, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw SceneError("--set '" + assignment + "': expected key.path=value");
  }
  const std::string path = assignment.substr(0, eq);
  const std::string value_text = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value_text);
  } catch (const toml::parse_error&) {
    // Bare words are strings: --set gas.thermo=calorically_perfect
    toml::table t;
    t.insert("v", value_text);
    parsed = std::move(t);
  }
  toml::table* cur = &doc;
  std::size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    const std::string part =
        path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (part.empty()) throw SceneError("--set '" + assignment + "': empty key segment");
    if (dot == std::string::npos) {
      cur->insert_or_assign(part, *parsed.get("v"));
      return path;
    }
    toml::node* next = cur->get(part);
    if (next == nullptr) {
      cur->insert(part, toml::table{});
      next = cur->get(part);
    }
    if (!next->is_table()) {
      throw SceneError("--set '" + assignment + "': '" + path.substr(0, dot) + "' is not a table");
    }
    cur = next->as_table();
    start = dot + 1;
  }
}

}  // namespace

namespace {

Scene parse_scene_into(const std::string& text, const std::string& name,
                       const std::vector<std::string>& overrides, ParseContext& context) {
  toml::table doc;
  try {
    doc = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << name << ":" << e.source().begin.line << ": TOML syntax error: " << e.description();
    throw SceneError(s.str());
  }
  for (const auto& o : overrides) context.overrides.emplace_back(apply_override(doc, o), o);

  Scene scene;
  scene.source_file = name;
  scene.source_text = text;
  scene.overrides = overrides;
  toml::table resolved;
  TableReader root(&doc, "", name, &resolved, &context);
  root.expect_keys(
      {"run", "grid", "gas", "boundary", "initial", "particles", "coupling", "output", "insitu"});
  using namespace scene_detail;
  parse_run(root.table("run"), scene.run);
  context.allow_implausible = scene.run.allow_implausible;
  // The floor may follow the layer's thickness (particles.layer.thickness): read before the grid.
  const std::optional<LayerFloor> floor = read_layer_floor(root);
  parse_grid(root.table("grid", true), scene.grid, floor);
  parse_gas(root.table("gas"), scene.gas);
  parse_boundary(root.table("boundary"), scene.gas.boundary, scene.gas.thermo);
  parse_initial(root.table("initial", true), scene.initial, scene.gas.thermo, scene.grid);
  // Particles larger than the cells are for a one-way run that averages the flow over them.
  TableReader coupling = root.lookahead("coupling");
  const bool larger_than_cells =
      coupling.boolean("finite_size", false) && !coupling.boolean("two_way", true);
  parse_particles(root.table("particles"), scene.particles, scene.grid, scene.gas.boundary,
                  larger_than_cells);
  parse_coupling(root.table("coupling"), scene.coupling, scene.particles, scene.grid);
  parse_output(root.table("output"), scene.output, scene.run, scene.particles, scene.grid);
  parse_insitu(root.table("insitu"), scene.insitu);
  root.finish();
  prune_empty_tables(resolved);

  // The inputs as values (running this text again gives the same scene), the defaults derived
  // from them as comments (so that changed inputs derive them again).
  std::ostringstream out;
  out << "# Resolved scene: every key with the value used (defaults filled in).\n"
      << "# Source: " << name << "\n";
  for (const auto& o : overrides) out << "# --set " << o << "\n";
  out << resolved << "\n";
  if (!context.derived.empty()) {
    out << "\n# Derived defaults: not set above, so computed from other keys when this file is "
           "read\n"
        << "# (values of this run; set a key to pin it):\n";
    for (const auto& d : context.derived) out << "#   " << d << "\n";
  }
  scene.resolved_toml = out.str();
  return scene;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name,
                  const std::vector<std::string>& overrides) {
  ParseContext context;
  return parse_scene_into(text, name, overrides, context);
}

std::map<std::string, KeyFact> read_scene_keys(const std::string& path) {
  ParseContext context;
  (void)parse_scene_into(read_input_file(path, "scene file"), path, {}, context);
  return context.keys;
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_scene(read_input_file(path, "scene file"), path, overrides);
}

}  // namespace dustlift
