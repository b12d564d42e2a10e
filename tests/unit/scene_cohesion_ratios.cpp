// The scene keys of the coarse graining per class (particles.parcel_ratio), the restitution per
// material and the cohesion ([particles.cohesion]): they resolve, read back, and every refusal
// names its key.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "solver/dem/contact_summary.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/laws/cohesion.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"

using namespace dustlift;

namespace {

const std::string kBase = R"(
[run]
end_time = 1e-4
[grid]
x = { start = 0.0, end = 0.04, cells = 40 }
y = { start = -0.002, end = 0.03, cells = 8 }
[initial]
kind = "uniform"
state = { p = 101325.0, T = 300.0 }
[particles]
density = 1300.0
[particles.contact]
k_n = 2e4
restitution = 0.9
[particles.layer]
x_max = 0.02
)";

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::string kClasses =
    "[particles.size_distribution]\ndiameters = [20e-6, 60e-6]\nmass_fractions = [0.4, 0.6]\n";

/// The scene with `extra` appended; one particle size (40 um) unless `extra` gives classes.
Scene parse(const std::string& extra, std::vector<std::string> overrides = {}) {
  const bool sized = has(extra, "size_distribution") || [&] {
    for (const std::string& o : overrides)
      if (has(o, "particles.diameter=")) return true;
    return false;
  }();
  if (!sized) overrides.push_back("particles.diameter=40e-6");
  return parse_scene(kBase + extra, "test.toml", overrides);
}

std::string error_of(const std::string& extra, std::vector<std::string> overrides = {}) {
  try {
    parse(extra, overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

const std::vector<std::string> kColumnar = {"particles.layer.arrangement=\"columnar\""};

}  // namespace

TEST(SceneParcelRatio, OneRatioGivesEachClassParcelsOfItsOwnSize) {
  const Scene s = parse(kClasses, {"particles.parcel_ratio=3", kColumnar[0]});
  const DemConfig& d = s.particles;
  ASSERT_EQ(d.size_classes.size(), 2u);
  EXPECT_DOUBLE_EQ(d.size_classes[0].parcel_diameter, 60e-6);
  EXPECT_DOUBLE_EQ(d.size_classes[1].parcel_diameter, 180e-6);
  EXPECT_DOUBLE_EQ(d.parcel_diameter, 180e-6);  // the largest class's parcels
  EXPECT_TRUE(has(describe_layer(d), "columns of one class each")) << describe_layer(d);
  EXPECT_TRUE(has(s.resolved_toml, "parcel_ratio = 3")) << s.resolved_toml;
  // The resolved scene reads back to the same parcels.
  const Scene again = parse_scene(s.resolved_toml, "resolved.toml");
  EXPECT_EQ(again.particles.size_classes[0].parcel_diameter, d.size_classes[0].parcel_diameter);
  const ParcelSystem layer = make_layer_system(d);
  EXPECT_GT(layer.size(), 1000u);
}

TEST(SceneParcelRatio, AListGivesOneRatioPerClass) {
  const Scene s = parse(
      "[particles.size_distribution]\ndiameters = [20e-6, 60e-6]\n"
      "mass_fractions = [0.4, 0.6]\n",
      {"particles.parcel_ratio=[4, 2]", kColumnar[0]});
  EXPECT_DOUBLE_EQ(s.particles.size_classes[0].parcel_diameter, 80e-6);
  EXPECT_DOUBLE_EQ(s.particles.size_classes[1].parcel_diameter, 120e-6);
}

TEST(SceneParcelRatio, OneSizeTakesTheRatioAsItsParcelDiameter) {
  const Scene s = parse("", {"particles.diameter=40e-6", "particles.parcel_ratio=2.5"});
  EXPECT_DOUBLE_EQ(s.particles.parcel_diameter, 100e-6);
  EXPECT_TRUE(s.particles.size_classes.empty());
}

TEST(SceneParcelRatio, BadRatiosAreNamed) {
  const std::string below = error_of(kClasses, {"particles.parcel_ratio=0.5", kColumnar[0]});
  EXPECT_TRUE(has(below, "particles.parcel_ratio") && has(below, ">= 1")) << below;
  const std::string length = error_of(kClasses, {"particles.parcel_ratio=[2, 3, 4]", kColumnar[0]});
  EXPECT_TRUE(has(length, "particles.parcel_ratio") && has(length, "2 size classes")) << length;
  const std::string one_size =
      error_of("", {"particles.diameter=40e-6", "particles.parcel_ratio=[2, 3]"});
  EXPECT_TRUE(has(one_size, "particles.parcel_ratio") && has(one_size, "size_distribution"))
      << one_size;
  const std::string both = error_of(
      kClasses, {"particles.parcel_ratio=2", kColumnar[0], "particles.parcel_diameter=100e-6"});
  EXPECT_TRUE(has(both, "particles.parcel_ratio") && has(both, "not both")) << both;
  const std::string lattice = error_of(kClasses, {"particles.parcel_ratio=2"});
  EXPECT_TRUE(has(lattice, "particles.parcel_ratio") && has(lattice, "columnar")) << lattice;
  // Spread columns hold the fraction in their discs; touching ones in their real particles.
  const std::string dense = error_of(
      kClasses, {"particles.parcel_ratio=2", kColumnar[0], "particles.layer.touching_columns=false",
                 "particles.layer.volume_fraction=0.85"});
  EXPECT_TRUE(has(dense, "particles.layer.volume_fraction")) << dense;
  const std::string touching_one_size = error_of(
      "", {"particles.diameter=40e-6", kColumnar[0], "particles.layer.touching_columns=true"});
  EXPECT_TRUE(has(touching_one_size, "particles.layer.touching_columns") &&
              has(touching_one_size, "size distribution"))
      << touching_one_size;
  // A cell smaller than the largest class's parcels.
  const std::string cell = error_of(kClasses, {"particles.parcel_ratio=30", kColumnar[0]});
  EXPECT_TRUE(has(cell, "particles.parcel_ratio")) << cell;
}

TEST(SceneRestitution, TheWallsTakeTheParticlesRestitution) {
  const Scene s = parse("");
  EXPECT_EQ(s.particles.contact.restitution, 0.9);
  EXPECT_EQ(s.particles.wall_contact.restitution, 0.9);
  EXPECT_GT(s.particles.wall_contact.damping, s.particles.contact.damping);  // m, not m/2
  EXPECT_TRUE(has(describe_contact_law(s.particles), "restitution 0.9 for every pair"));
  // A wall dashpot of its own keeps it.
  const Scene own = parse("[particles.wall_contact]\ndamping = 1e-5\n");
  EXPECT_EQ(own.particles.wall_contact.restitution, 0.0);
  EXPECT_EQ(own.particles.wall_contact.damping, 1e-5);
}

TEST(SceneCohesion, HamakerConstantOrSurfaceEnergy) {
  const Scene off = parse("");
  EXPECT_FALSE(off.particles.cohesion.enabled());
  EXPECT_FALSE(has(off.resolved_toml, "cohesion"));  // nothing read, nothing written
  const Scene s = parse("[particles.cohesion]\nhamaker = 1e-19\nasperity_radius = 0.1e-6\n");
  const DemConfig& d = s.particles;
  EXPECT_EQ(d.cohesion.hamaker, 1e-19);
  EXPECT_EQ(d.cohesion.min_separation, 4e-10);
  EXPECT_EQ(d.wall_cohesion.hamaker, 1e-19);  // the wall: the same material by default
  EXPECT_EQ(d.wall_cohesion.asperity_radius, 0.1e-6);
  const std::vector<std::string> lines = contact_descriptions(d);
  ASSERT_EQ(lines.size(), 1u);
  const std::string& line = lines[0];
  EXPECT_TRUE(has(line, "pull-off force") && has(line, "Bond number")) << line;
  const Scene gamma = parse("[particles.cohesion]\nsurface_energy = 8.289e-3\nwall_hamaker = 0\n");
  EXPECT_NEAR(gamma.particles.cohesion.hamaker, 1e-19, 1e-22);
  EXPECT_FALSE(gamma.particles.wall_cohesion.enabled());
  const Scene again = parse_scene(s.resolved_toml, "resolved.toml");
  EXPECT_EQ(again.particles.cohesion.hamaker, 1e-19);
}

TEST(SceneCohesion, BadCohesionIsNamed) {
  const std::string negative = error_of("[particles.cohesion]\nhamaker = -1e-19\n");
  EXPECT_TRUE(has(negative, "particles.cohesion.hamaker") && has(negative, ">= 0")) << negative;
  const std::string gamma = error_of("[particles.cohesion]\nsurface_energy = -0.01\n");
  EXPECT_TRUE(has(gamma, "particles.cohesion.surface_energy") && has(gamma, ">= 0")) << gamma;
  const std::string both =
      error_of("[particles.cohesion]\nhamaker = 1e-19\nsurface_energy = 0.01\n");
  EXPECT_TRUE(has(both, "particles.cohesion.surface_energy") && has(both, "not both")) << both;
  const std::string separation =
      error_of("[particles.cohesion]\nhamaker = 1e-19\nmin_separation = 0\n");
  EXPECT_TRUE(has(separation, "particles.cohesion.min_separation")) << separation;
  const std::string cutoff = error_of("[particles.cohesion]\nhamaker = 1e-19\ncutoff = 1e-3\n");
  EXPECT_TRUE(has(cutoff, "particles.cohesion.cutoff") && has(cutoff, "parcel_diameter")) << cutoff;
  const std::string unknown = error_of("[particles.cohesion]\nhamakr = 1e-19\n");
  EXPECT_TRUE(has(unknown, "particles.cohesion.hamakr")) << unknown;
}
