// scene.resolved.toml holds the inputs with every default: it runs again as it is and gives
// the same result bit for bit, and it does not pin values derived from other keys (they are
// comments), so a resolved scene with a changed input derives them again.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>

#include "insitu/checkpoint.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"
#include "support/run_cli.hpp"
#include "support/snapshot_compare.hpp"

namespace fs = std::filesystem;
using namespace dustlift;
using dustlift::testing::expect_bitwise_equal;
using dustlift::testing::fresh_dir;
using dustlift::testing::read_bytes;
using dustlift::testing::run_cli;

namespace {

/// The resolved text without the lines that name where it came from.
std::string without_origin(const std::string& resolved) {
  std::istringstream in(resolved);
  std::string line, kept;
  while (std::getline(in, line)) {
    if (line.rfind("# Source:", 0) == 0 || line.rfind("# --set", 0) == 0) continue;
    kept += line + "\n";
  }
  return kept;
}

std::vector<fs::path> shipped_scenes() {
  std::vector<fs::path> scenes;
  for (const auto& e : fs::recursive_directory_iterator(std::string(DUSTLIFT_SOURCE_DIR) + "/cases")) {
    if (e.path().extension() == ".toml" && e.path().string().find("/studies/") == std::string::npos) scenes.push_back(e.path());
  }
  return scenes;
}

}  // namespace

TEST(ResolvedScene, EveryShippedSceneParsesBackToTheSameResolvedScene) {
  const auto scenes = shipped_scenes();
  ASSERT_GE(scenes.size(), 12u);
  for (const fs::path& path : scenes) {
    SCOPED_TRACE(path.string());
    const Scene first = load_scene(path.string());
    const Scene again = parse_scene(first.resolved_toml, "resolved.toml");
    EXPECT_EQ(without_origin(again.resolved_toml), without_origin(first.resolved_toml));
    EXPECT_EQ(again.particles.real_per_parcel, first.particles.real_per_parcel);
    EXPECT_EQ(again.particles.parcel_diameter, first.particles.parcel_diameter);
    EXPECT_EQ(again.output.bands.size(), first.output.bands.size());
    EXPECT_EQ(again.output.surface_stations, first.output.surface_stations);
    EXPECT_EQ(again.output.checkpoint_interval, first.output.checkpoint_interval);
  }
}

TEST(ResolvedScene, RunsAgainToTheSameStateBitForBit) {
  // The quickstart reduced to a 30 mm channel, 20 steps: once from its file, once from the
  // resolved scene (parsed from its text alone).
  const std::vector<std::string> reduce = {"grid.x.start=-0.01", "grid.x.end=0.02", "grid.x.cells_below=4",
                                           "grid.y.end=0.006", "grid.y.uniform_end=0.004", "grid.y.cells_above=2", "particles.layer.x_max=0.02"};
  const Scene scene = load_scene(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml", reduce);
  const Scene resolved = parse_scene(scene.resolved_toml, "scene.resolved.toml");
  Simulation a(scene), b(resolved);
  ASSERT_GE(a.parcels()->size(), 3000u);
  for (int k = 0; k < 20; ++k) {
    a.advance(1.0);
    b.advance(1.0);
  }
  expect_bitwise_equal(a.snapshot(), b.snapshot());
  EXPECT_GT(a.time(), 0.0);
}

TEST(ResolvedScene, DerivedDefaultsAreCommentsSoChangedInputsDeriveThemAgain) {
  const Scene scene = load_scene(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml");
  const std::string& text = scene.resolved_toml;
  // Written as values: inputs and plain defaults; as comments: what other keys decide.
  EXPECT_NE(text.find("diameter = 0.0001\n"), std::string::npos);
  EXPECT_NE(text.find("courant = 0.10000000000000001"), std::string::npos) << "a plain default, written";
  for (const char* derived : {"particles.parcel_diameter = ", "particles.real_per_parcel = ", "coupling.influence_width = ",
                              "output.band_duration = ", "output.bands = [{ name = \"surface\"", "output.surface_stations = [",
                              "output.checkpoint_interval = ", "particles.wall_contact.k_n = "}) {
    EXPECT_NE(text.find("#   " + std::string(derived)), std::string::npos) << derived << "\n" << text;
  }
  EXPECT_EQ(text.find("\nparcel_diameter ="), std::string::npos) << "not pinned as a value";
  // The resolved scene with a smaller particle and a later end: the derived values follow.
  const Scene changed = parse_scene(text, "scene.resolved.toml", {"particles.diameter=50e-6", "run.end_time=4e-4"});
  EXPECT_EQ(changed.particles.parcel_diameter, 50e-6);
  EXPECT_EQ(changed.coupling.influence_width, 50e-6);
  EXPECT_NE(changed.particles.real_per_parcel, scene.particles.real_per_parcel);
  EXPECT_EQ(changed.output.band_duration, 4e-4);
  EXPECT_EQ(scene.output.band_duration, 3e-4);
  ASSERT_EQ(changed.output.bands.size(), 2u);
  EXPECT_EQ(changed.output.bands[0].name, "surface");
}

TEST(ResolvedScene, TheResolvedSceneOfARunFolderRunsThroughTheCli) {
  const auto dir = fresh_dir("resolved_cli");
  const std::string sod = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/sod.toml";
  auto r = run_cli("run " + sod + " --out " + (dir / "first").string() + " --set grid.x.cells=80 --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string resolved = (dir / "first" / "scene.resolved.toml").string();
  EXPECT_NE(read_bytes(resolved).find("# Written by dustlift "), std::string::npos);
  r = run_cli("run " + resolved + " --out " + (dir / "again").string() + " --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Snapshot a = read_checkpoint((dir / "first" / "checkpoint.h5").string());
  const Snapshot b = read_checkpoint((dir / "again" / "checkpoint.h5").string());
  expect_bitwise_equal(a, b);
  EXPECT_EQ(read_bytes(dir / "first" / "series" / "shock_position.csv"), read_bytes(dir / "again" / "series" / "shock_position.csv"));
  fs::remove_all(dir);
}
