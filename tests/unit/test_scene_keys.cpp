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
