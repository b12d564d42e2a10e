#pragma once
// The scene keys' documentation: unit and meaning of every key the parser declares. Together
// with what the parser records as it reads (KeyFact: type, default or what a default is
// derived from, allowed range), this is the scene-key reference `dustlift info --keys` prints
// and docs/reference/scene-keys.md holds; a test fails when a key the parser declares has no
// entry here, when an entry names no key, or when the generated reference is stale.
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "solver/scene/table_reader.hpp"

namespace dustlift {

/// One documented key. `pattern` is the dotted key; a segment "*" stands for any one segment
/// (grid.*.cells: grid.x.cells and grid.y.cells).
struct SceneKeyDoc {
  std::string_view pattern;
  std::string_view unit;     ///< SI unit, "1" for a dimensionless number, "" for none
  std::string_view meaning;  ///< one line
};

/// Every documented key, in the order of the reference (by section).
std::span<const SceneKeyDoc> scene_key_docs();

/// The documentation entry whose pattern matches `key` (a reference key: no array indices);
/// null when none does.
const SceneKeyDoc* find_key_doc(std::string_view key);

/// The reference of the keys the given facts name (merged over several scenes), one row per
/// documented pattern, as a Markdown document: section, key, type, unit, default, allowed,
/// meaning. Facts of keys without an entry are listed under "Undocumented" (the test fails
/// on them).
std::string key_reference_markdown(const std::map<std::string, KeyFact>& facts);

/// Merges the facts of one scene into `into`: a key whose default differs between scenes
/// gets "depends on the scene" (its derived-from text is kept when one says it).
void merge_key_facts(std::map<std::string, KeyFact>& into,
                     const std::map<std::string, KeyFact>& from);

}  // namespace dustlift
