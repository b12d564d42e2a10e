// The scene-key reference: every key the parser declares is documented, every documented key is
// read by some scene of the repository, and docs/reference/scene-keys.md is the reference those
// scenes generate (scripts/scene-keys.sh).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/scene/scene_keys.hpp"

namespace fs = std::filesystem;

namespace dustlift {
namespace {

/// The scenes scripts/scene-keys.sh reads, in the same (byte) order.
std::vector<std::string> repository_scenes() {
  std::vector<std::string> scenes;
  for (const auto& e :
       fs::recursive_directory_iterator(std::string(DUSTLIFT_SOURCE_DIR) + "/cases"))
    if (e.path().extension() == ".toml" && e.path().string().find("/studies/") == std::string::npos)
      scenes.push_back(e.path().string());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

std::map<std::string, KeyFact> repository_facts() {
  std::map<std::string, KeyFact> facts;
  for (const std::string& path : repository_scenes()) merge_key_facts(facts, read_scene_keys(path));
  return facts;
}

TEST(SceneKeys, EveryKeyTheParserDeclaresIsDocumented) {
  for (const auto& [key, fact] : repository_facts()) EXPECT_NE(find_key_doc(key), nullptr) << key;
}

TEST(SceneKeys, EveryDocumentedKeyIsReadBySomeSceneWithItsTypeAndDefault) {
  const auto facts = repository_facts();
  for (const SceneKeyDoc& d : scene_key_docs()) {
    bool read = false;
    for (const auto& [key, fact] : facts)
      read = read || (find_key_doc(key) == &d && !fact.kind.empty() && !fact.fallback.empty());
    EXPECT_TRUE(read) << d.pattern << ": no scene in cases/ reads it";
  }
}

TEST(SceneKeys, TheParserRecordsItsOwnDefaultsAndRanges) {
  const auto facts = read_scene_keys(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml");
  // A literal default, a range, a derived default and a choice, as the parser reads them.
  EXPECT_EQ(facts.at("particles.courant").fallback, "0.1");
  EXPECT_EQ(facts.at("particles.courant").range, "in (0, 0.5]");
  EXPECT_EQ(facts.at("particles.parcel_diameter").fallback,
            "from particles.diameter (no coarse graining)");
  EXPECT_EQ(facts.at("coupling.volume_fraction_correction").kind, "one of");
  EXPECT_EQ(facts.at("coupling.volume_fraction_correction").range,
            "\"sangani\", \"osnes\", \"tenneti\", \"linear\", \"none\"");
  EXPECT_EQ(facts.at("run.end_time").fallback, "required");
}

TEST(SceneKeys, TheReferenceRangesAreTheParsersLimitsNotOneScenesNumbers) {
  // Every scene that reads a key records the same allowed range: a range set by other keys
  // is named by them, not by the numbers of the scene that happened to be read.
  std::map<std::string, std::pair<std::string, std::string>> first;  // key -> (range, scene)
  for (const std::string& path : repository_scenes()) {
    for (const auto& [key, fact] : read_scene_keys(path)) {
      const auto [it, inserted] = first.try_emplace(key, fact.range, path);
      if (!inserted && !fact.range.empty() && !it->second.first.empty()) {
        EXPECT_EQ(fact.range, it->second.first)
            << key << ": " << path << " against " << it->second.second;
      }
    }
  }
  const auto facts = repository_facts();
  EXPECT_EQ(facts.at("output.probes.x").range, "in [grid.x.start, grid.x.end]");
  EXPECT_EQ(facts.at("output.probes.y").range, "in [grid.y.start, grid.y.end]");
  EXPECT_EQ(facts.at("particles.layer.loose_top_rows").range, "in [0, the layer's rows]");
  // What the range says is what the parser accepts: a probe at x = 0.12 m in a channel to
  // 0.15 m (the quickstart) is read; one beyond the channel is refused with its numbers.
  const std::string scene = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";
  std::ifstream in(scene);
  std::stringstream text;
  text << in.rdbuf();
  const std::string probe = "\n[[output.probes]]\nname = \"gauge\"\ny = 0.001\nx = ";
  EXPECT_DOUBLE_EQ(parse_scene(text.str() + probe + "0.12\n", scene).output.probes.at(0).x, 0.12);
  try {
    (void)parse_scene(text.str() + probe + "0.2\n", scene);
    ADD_FAILURE() << "a probe outside the grid must be refused";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "value 0.2 out of range: must be in [-0.06, 0.15], i.e. in [grid.x.start, "
                  "grid.x.end]"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneKeys, TypesChoicesAndPerAxisDefaultsAreRight) {
  const auto facts = repository_facts();
  // Every choice key lists its allowed values.
  for (const auto& [key, fact] : facts)
    if (fact.kind == "one of") {
      EXPECT_FALSE(fact.range.empty()) << key;
    }
  EXPECT_EQ(facts.at("particles.layer.arrangement").kind, "one of");
  EXPECT_EQ(
      facts.at("particles.layer.arrangement").range,
      "\"jittered_lattice\", \"lattice\", \"columnar\", \"hexagonal\", \"settled\", \"file\"");
  EXPECT_EQ(facts.at("output.probes.fields").range,
            "each one of \"p\", \"rho\", \"u\", \"v\", \"T\", \"mach\", \"alpha_p\"");
  // A key of two forms has both in its type.
  EXPECT_EQ(facts.at("particles.gravity").kind, "boolean or list of numbers");
  // The derived-from text of each axis names that axis; the floor may follow the thickness.
  EXPECT_EQ(facts.at("grid.x.uniform_start").fallback, "from grid.x.start");
  EXPECT_EQ(facts.at("grid.y.uniform_start").fallback, "from grid.y.start");
  const std::string md = key_reference_markdown(facts);
  EXPECT_NE(md.find("| `grid.*.uniform_start` | number | m | from grid.*.start |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("from grid.x.start"), std::string::npos) << "no y-axis row may name the x axis";
  EXPECT_NE(md.find("| `grid.x.start` | number | m | required |"), std::string::npos);
  EXPECT_NE(md.find("| `grid.y.start` | number | m | required, or from particles.layer.thickness"),
            std::string::npos);
  EXPECT_NE(md.find("| `particles.layer.thickness` | number | m | optional | > 0 |"),
            std::string::npos);
  EXPECT_NE(md.find("| `run.allow_implausible` | boolean |  | false |"), std::string::npos);
}

TEST(SceneKeys, TheGeneratedReferenceIsUpToDate) {
  const std::string generated = key_reference_markdown(repository_facts());
  EXPECT_EQ(generated.find("## Undocumented"), std::string::npos) << generated;
  std::ifstream in(std::string(DUSTLIFT_SOURCE_DIR) + "/docs/reference/scene-keys.md");
  std::stringstream file;
  file << in.rdbuf();
  EXPECT_EQ(file.str(), generated)
      << "docs/reference/scene-keys.md is stale: run bash scripts/scene-keys.sh";
}

}  // namespace
}  // namespace dustlift
