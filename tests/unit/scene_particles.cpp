// The [particles] scene section: defaults are the paper's, errors name the key; the size
// classes of [particles.size_distribution] resolve and every refusal names its key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "solver/dem/layer_generator.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"

using namespace dustlift;

namespace {

const std::string kBase = R"(
[run]
end_time = 1e-4
[grid]
x = { start = 0.0, end = 0.4, cells = 40 }
y = { start = -0.002, end = 0.03, cells = 8 }
[initial]
kind = "uniform"
state = { p = 101325.0, T = 300.0 }
)";

/// The dust's material as the paper's (Tables 1, 2), for the keys `particles` does not set:
/// a scene must give them (test MaterialHasNoDefaults), these tests are about the rest.
std::vector<std::string> paper_material(const std::string& particles) {
  if (particles.find("[particles") == std::string::npos) return {};
  std::vector<std::string> o;
  const auto sets = [&](const char* key) { return particles.find(std::string("\n") + key + " =") != std::string::npos; };
  if (!sets("diameter") && particles.find("[particles.size_distribution]") == std::string::npos)
    o.push_back("particles.diameter=100e-6");
  if (!sets("density")) o.push_back("particles.density=980.0");
  if (!sets("k_n")) o.push_back("particles.contact.k_n=5e4");
  if (!sets("damping") && !sets("restitution")) o.push_back("particles.contact.damping=1e-4");
  return o;
}

Scene parse(const std::string& particles) {
  return parse_scene(kBase + particles, "test.toml", paper_material(particles));
}

/// The SceneError message of parsing `particles`, or "" if it parsed.
std::string error_of(const std::string& particles) {
  try {
    parse(particles);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

/// The same without the paper's material filled in.
std::string raw_error_of(const std::string& particles) {
  try {
    parse_scene(kBase + particles, "test.toml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::string kDiscrete = "[particles]\n[particles.size_distribution]\n";

}  // namespace

TEST(SceneParticles, AbsentSectionDisablesParcels) {
  const Scene s = parse("");
  EXPECT_FALSE(s.particles.enabled);
}

TEST(SceneParticles, MaterialHasNoDefaults) {
  // The dust's size, density, stiffness and damping are the user's: each missing one is named.
  EXPECT_TRUE(has(raw_error_of("[particles]\n"), "particles.diameter")) << raw_error_of("[particles]\n");
  EXPECT_TRUE(has(raw_error_of("[particles]\ndiameter = 1e-4\n"), "particles.density"));
  EXPECT_TRUE(has(raw_error_of("[particles]\ndiameter = 1e-4\ndensity = 980.0\n"), "particles.contact"));
  const std::string material = "[particles]\ndiameter = 1e-4\ndensity = 980.0\n[particles.contact]\n";
  EXPECT_TRUE(has(raw_error_of(material), "particles.contact.k_n"));
  const std::string damping = raw_error_of(material + "k_n = 5e4\n");
  EXPECT_TRUE(has(damping, "particles.contact.damping") && has(damping, "restitution")) << damping;
  EXPECT_EQ(raw_error_of(material + "k_n = 5e4\nrestitution = 0.957\n"), "");
}

TEST(SceneParticles, EmptySectionGivesThePaperDefaults) {
  const Scene s = parse("[particles]\n");
  const DemConfig& d = s.particles;
  EXPECT_TRUE(d.enabled);
  EXPECT_EQ(d.particle_diameter, 100e-6);
  EXPECT_EQ(d.density, 980.0);
  EXPECT_EQ(d.heat_capacity, 1200.0);
  EXPECT_EQ(d.initial_temperature, 300.0);
  EXPECT_EQ(d.parcel_diameter, 100e-6);
  EXPECT_EQ(d.layer.volume_fraction, 0.59);
  EXPECT_EQ(d.layer.x_max, 0.4);
  EXPECT_EQ(d.layer.y_min, -0.002);
  EXPECT_EQ(d.layer.y_max, 0.0);
  EXPECT_EQ(d.contact.k_n, 5e4);
  EXPECT_EQ(d.contact.k_t, 100.0);
  EXPECT_EQ(d.contact.damping, 1e-4);
  EXPECT_EQ(d.wall_contact.k_n, d.contact.k_n);
  EXPECT_EQ(d.wall_contact.friction, d.contact.friction);
  EXPECT_EQ(d.gravity_y, 0.0);
  EXPECT_TRUE(d.domain.wall_bottom);
  EXPECT_EQ(d.domain.y_min, -0.002);
  // Derived real particles per parcel: 0.59 * 8e-4 m^2 / (60,097 V_p) = 15,000 per metre.
  EXPECT_NEAR(d.real_per_parcel, 15000.0, 2.0);
  // The resolved scene records the derived value.
  EXPECT_NE(s.resolved_toml.find("real_per_parcel"), std::string::npos);
}

TEST(SceneParticles, GoodSectionParses) {
  const Scene s = parse(R"(
[particles]
diameter = 50e-6
parcel_diameter = 100e-6
density = 2500.0
real_per_parcel = 20000.0
courant = 0.05
gravity = true
[particles.layer]
x_min = 0.0
x_max = 0.05
y_min = -0.001
y_max = 0.0
volume_fraction = 0.4
seed = 9
arrangement = "lattice"
[particles.contact]
k_n = 1e5
k_t = 200.0
damping = 2e-4
friction = 0.3
[particles.wall_contact]
coulomb = false
[boundary]
left = "periodic"
right = "periodic"
)");
  const DemConfig& d = s.particles;
  EXPECT_EQ(d.particle_diameter, 50e-6);
  EXPECT_EQ(d.parcel_diameter, 100e-6);
  EXPECT_EQ(d.real_per_parcel, 20000.0);
  EXPECT_EQ(d.courant, 0.05);
  EXPECT_EQ(d.gravity_y, -9.81);
  EXPECT_EQ(d.layer.seed, 9u);
  EXPECT_EQ(d.layer.arrangement, LayerArrangement::Lattice);
  EXPECT_EQ(d.contact.friction, 0.3);
  EXPECT_EQ(d.wall_contact.k_n, 1e5);  // wall defaults follow the particle contact
  EXPECT_TRUE(std::isinf(d.wall_contact.friction));
  // The parcels' domain is the gas grid; periodic gas boundaries make the parcels periodic.
  EXPECT_TRUE(d.domain.periodic_x);
  EXPECT_FALSE(d.domain.wall_left);
  EXPECT_TRUE(d.domain.wall_top);
  EXPECT_EQ(d.domain.y_max, 0.03);
}

TEST(SceneParticles, UnknownKeyIsNamed) {
  const std::string e = error_of("[particles]\nstifness = 3\n");
  EXPECT_NE(e.find("particles.stifness"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
  const std::string f = error_of("[particles.contact]\nk_normal = 3\n");
  EXPECT_NE(f.find("particles.contact.k_normal"), std::string::npos) << f;
}

TEST(SceneParticles, NegativeDiameterIsNamed) {
  const std::string e = error_of("[particles]\ndiameter = -1e-4\n");
  EXPECT_NE(e.find("particles.diameter"), std::string::npos) << e;
  EXPECT_NE(e.find("out of range"), std::string::npos) << e;
}

TEST(SceneParticles, VolumeFractionAtOrAbove0p9IsNamed) {
  for (const char* v : {"0.9", "0.95"}) {
    const std::string e = error_of(std::string("[particles.layer]\nvolume_fraction = ") + v + "\n");
    EXPECT_NE(e.find("particles.layer.volume_fraction"), std::string::npos) << e;
  }
  // Below 0.9 but too dense for the lattice generator: still an error on the same key.
  const std::string e = error_of("[particles.layer]\nvolume_fraction = 0.85\n");
  EXPECT_NE(e.find("particles.layer.volume_fraction"), std::string::npos) << e;
}

TEST(SceneParticles, InconsistentSettingsAreNamed) {
  EXPECT_NE(error_of("[particles]\nparcel_diameter = 50e-6\n").find("particles.parcel_diameter"), std::string::npos);
  EXPECT_NE(error_of("[particles.layer]\nx_max = 0.5\n").find("particles.layer"), std::string::npos);
  EXPECT_NE(error_of("[particles.contact]\ncoulomb = false\nfriction = 0.2\n").find("particles.contact.friction"),
            std::string::npos);
}

TEST(SceneParticles, LooseTopIsParsedAndItsMistakesAreNamed) {
  const Scene s = parse(
      "[particles.layer]\narrangement = \"columnar\"\nloose_top_rows = 2\nloose_top_fill = 0.5\n");
  EXPECT_EQ(s.particles.layer.loose_top_rows, 2);
  EXPECT_EQ(s.particles.layer.loose_top_fill, 0.5);
  // real_per_parcel as without the loose top: the rows below hold the volume fraction.
  const Scene full = parse("[particles.layer]\narrangement = \"columnar\"\n");
  EXPECT_EQ(s.particles.real_per_parcel, full.particles.real_per_parcel);
  const std::string rows =
      error_of("[particles.layer]\narrangement = \"columnar\"\nloose_top_rows = 21\n");
  EXPECT_NE(rows.find("particles.layer.loose_top_rows"), std::string::npos) << rows;
  EXPECT_NE(rows.find("[0, 20]"), std::string::npos)
      << rows << " (the columnar paper layer has 20 rows)";
  for (const char* fill : {"0", "1.5", "-0.5"}) {
    const std::string e = error_of(
        std::string("[particles.layer]\nloose_top_rows = 1\nloose_top_fill = ") + fill + "\n");
    EXPECT_NE(e.find("particles.layer.loose_top_fill"), std::string::npos) << e;
  }
  const std::string alone = error_of("[particles.layer]\nloose_top_fill = 0.5\n");
  EXPECT_NE(alone.find("particles.layer.loose_top_fill"), std::string::npos) << alone;
  EXPECT_NE(alone.find("loose_top_rows"), std::string::npos) << alone;
}

// ---- [particles.size_distribution]: polydisperse layers (docs/dem.md) ----


TEST(SceneSizeDistribution, DiscreteClassesResolve) {
  const Scene s = parse(kDiscrete + "diameters = [50e-6, 100e-6]\nmass_fractions = [0.3, 0.7]\n");
  const DemConfig& d = s.particles;
  ASSERT_EQ(d.size_classes.size(), 2u);
  EXPECT_EQ(d.size_classes[0].diameter, 50e-6);
  EXPECT_EQ(d.size_classes[1].mass_fraction, 0.7);
  EXPECT_EQ(d.particle_diameter, 100e-6);  // the mass median
  EXPECT_EQ(d.parcel_diameter, 100e-6);    // the largest class: no coarse graining of it
  EXPECT_EQ(d.real_per_parcel, 0.0);       // per class
  EXPECT_TRUE(has(s.resolved_toml, "diameters = [ 5.0000000000000002e-05, 0.0001 ]"))
      << s.resolved_toml;
  EXPECT_TRUE(has(describe_layer(d), "size classes (2): 50 um, ")) << describe_layer(d);
}

TEST(SceneSizeDistribution, LognormalClassesResolveAndShowInTheResolvedScene) {
  const Scene s = parse(
      "[particles]\nparcel_diameter = 150e-6\n[particles.size_distribution]\nmedian = 50e-6\n"
      "geometric_std = 2.0\n");
  const DemConfig& d = s.particles;
  ASSERT_EQ(d.size_classes.size(), 5u);  // the default count
  EXPECT_NEAR(d.size_classes[4].diameter, 121.5501408844856e-6, 1e-18);
  EXPECT_EQ(d.particle_diameter, 50e-6);  // the mass median given, whatever the class count
  EXPECT_TRUE(has(s.resolved_toml, "particles.size_distribution.diameters = [2.0567643787232"))
      << s.resolved_toml;
  EXPECT_TRUE(has(s.resolved_toml, "particles.size_distribution.mass_fractions = [0.2"))
      << s.resolved_toml;
  EXPECT_TRUE(has(s.resolved_toml, "particles.real_per_parcel = [")) << s.resolved_toml;
  // The resolved scene parses back to the same classes.
  const Scene again = parse_scene(s.resolved_toml, "resolved.toml");
  ASSERT_EQ(again.particles.size_classes.size(), 5u);
  EXPECT_EQ(again.particles.size_classes[0].diameter, d.size_classes[0].diameter);
}

TEST(SceneSizeDistribution, MassFractionsNotSummingToOneAreNamed) {
  const std::string e =
      error_of(kDiscrete + "diameters = [50e-6, 100e-6]\nmass_fractions = [0.3, 0.6]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.mass_fractions") && has(e, "not 1")) << e;
}

TEST(SceneSizeDistribution, GeometricStdAtMostOneIsNamed) {
  const std::string e = error_of(kDiscrete + "median = 50e-6\ngeometric_std = 1.0\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.geometric_std") && has(e, "must be > 1")) << e;
}

TEST(SceneSizeDistribution, ClassLargerThanTheSmallestCellIsNamed) {
  // Cells of 0.4 / 400 = 1 mm along x; the layer 4 mm deep.
  std::string text = kBase;
  text.replace(text.find("cells = 40"), 10, "cells = 400");
  text +=
      "[particles]\n[particles.size_distribution]\n"
      "diameters = [0.5e-3, 1.5e-3]\nmass_fractions = [0.5, 0.5]\n";
  std::string message;
  try {
    parse_scene(text, "test.toml", paper_material(text));
  } catch (const SceneError& err) {
    message = err.what();
  }
  EXPECT_TRUE(has(message, "particles.size_distribution.diameters") &&
              has(message, "smallest grid cell"))
      << message;
}

TEST(SceneSizeDistribution, ClassLargerThanTheLayerDepthIsNamed) {
  const std::string e =
      error_of(kDiscrete + "diameters = [50e-6, 2.5e-3]\nmass_fractions = [0.5, 0.5]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.diameters") && has(e, "layer's depth")) << e;
}

TEST(SceneSizeDistribution, ClassLargerThanTheParcelIsNamed) {
  const std::string e = error_of(
      "[particles]\nparcel_diameter = 80e-6\n[particles.size_distribution]\n"
      "diameters = [50e-6, 100e-6]\nmass_fractions = [0.6, 0.4]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.diameters") && has(e, "parcel_diameter")) << e;
  const std::string l = error_of(
      "[particles]\nparcel_diameter = 80e-6\n[particles.size_distribution]\n"
      "median = 50e-6\ngeometric_std = 2.0\n");
  EXPECT_TRUE(has(l, "particles.size_distribution.median") && has(l, "parcel_diameter")) << l;
}

TEST(SceneSizeDistribution, ClassWithoutParcelIsNamed) {
  // 60,097 parcels: a share of 1e-6 rounds to no parcel.
  const std::string e =
      error_of(kDiscrete + "diameters = [50e-6, 100e-6]\nmass_fractions = [0.999999, 0.000001]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.mass_fractions") && has(e, "gets no parcel"))
      << e;
  // A tiny layer of 4 parcels cannot hold 5 classes.
  const std::string l = error_of(
      "[particles]\n[particles.layer]\nx_max = 0.0004\ny_min = -0.0002\nvolume_fraction = 0.2\n"
      "[particles.size_distribution]\nmedian = 50e-6\ngeometric_std = 1.5\n");
  EXPECT_TRUE(has(l, "particles.size_distribution.classes") && has(l, "gets no parcel")) << l;
}

TEST(SceneSizeDistribution, NonAscendingDiametersAreNamed) {
  const std::string e =
      error_of(kDiscrete + "diameters = [100e-6, 50e-6]\nmass_fractions = [0.5, 0.5]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.diameters") && has(e, "ascending")) << e;
}

TEST(SceneSizeDistribution, NonPositiveDiametersAreNamed) {
  const std::string e =
      error_of(kDiscrete + "diameters = [0.0, 50e-6]\nmass_fractions = [0.5, 0.5]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.diameters")) << e;
}

TEST(SceneSizeDistribution, ListsOfDifferentLengthsAreNamed) {
  const std::string e =
      error_of(kDiscrete + "diameters = [50e-6, 100e-6]\nmass_fractions = [1.0]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.mass_fractions") &&
              has(e, "one fraction per class"))
      << e;
}

TEST(SceneSizeDistribution, BothFormsAtOnceAreNamed) {
  const std::string e =
      error_of(kDiscrete + "diameters = [50e-6]\nmass_fractions = [1.0]\nmedian = 50e-6\n");
  EXPECT_TRUE(has(e, "particles.size_distribution.median") && has(e, "not both")) << e;
}

TEST(SceneSizeDistribution, ParticleDiameterWithADistributionIsNamed) {
  const std::string e = error_of(
      "[particles]\ndiameter = 100e-6\n[particles.size_distribution]\n"
      "diameters = [50e-6, 100e-6]\nmass_fractions = [0.5, 0.5]\n");
  EXPECT_TRUE(has(e, "particles.diameter") && has(e, "mass median")) << e;
}

TEST(SceneSizeDistribution, RealPerParcelWithADistributionIsNamed) {
  const std::string e = error_of(
      "[particles]\nreal_per_parcel = 1000.0\n[particles.size_distribution]\n"
      "diameters = [50e-6, 100e-6]\nmass_fractions = [0.5, 0.5]\n");
  EXPECT_TRUE(has(e, "particles.real_per_parcel") && has(e, "each size class")) << e;
}

TEST(SceneSizeDistribution, LayerFileWithADistributionIsNamed) {
  const auto dir = std::filesystem::temp_directory_path() / "dustlift_size_distribution_file";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "layer.csv") << "x,y\n0.01,-0.001\n";
  const std::string e =
      error_of("[particles]\n[particles.layer]\narrangement = \"file\"\nfile = \"" +
               (dir / "layer.csv").string() +
               "\"\n[particles.size_distribution]\ndiameters = [50e-6, 100e-6]\nmass_fractions = "
               "[0.5, 0.5]\n");
  EXPECT_TRUE(has(e, "particles.size_distribution") && has(e, "particle_diameter column")) << e;
  std::filesystem::remove_all(dir);
}

TEST(SceneSizeDistribution, LayerFileParticleDiametersAreItsClasses) {
  const auto dir = std::filesystem::temp_directory_path() / "dustlift_size_distribution_classes";
  std::filesystem::create_directories(dir);
  // Two parcels of 50 um particles (one twice the area), one of 100 um: mass shares by the
  // solid each holds, (D / D_ref)^2.
  std::ofstream(dir / "layer.csv")
      << "x,y,diameter,particle_diameter\n0.01,-0.001,100e-6,50e-6\n"
         "0.02,-0.001,141.42135623730951e-6,50e-6\n0.03,-0.001,100e-6,100e-6\n";
  const Scene s = parse("[particles]\n[particles.layer]\narrangement = \"file\"\nfile = \"" +
                        (dir / "layer.csv").string() + "\"\n");
  const DemConfig& d = s.particles;
  ASSERT_EQ(d.size_classes.size(), 2u);
  EXPECT_EQ(d.size_classes[0].diameter, 50e-6);
  EXPECT_NEAR(d.size_classes[0].mass_fraction, 0.75, 1e-12);
  const ParcelSystem ps = make_layer_system(d);
  ASSERT_EQ(ps.size(), 3u);
  // The 50 um parcel holds (100/50)^3 = 8 times the particles of the 100 um one: same solid.
  EXPECT_NEAR(ps.n_real[0], 8.0 * ps.n_real[2], 1e-9 * ps.n_real[0]);
  EXPECT_EQ(ps.size_class[0], 0.0);
  EXPECT_EQ(ps.size_class[2], 1.0);
  EXPECT_EQ(ps.real_diameter[0], 50e-6);
  EXPECT_TRUE(has(describe_layer(d),
                  "size classes (2): 50 um, 2 parcels, mass fraction 0.75; 100 um, 1 "
                  "parcels, mass fraction 0.25"))
      << describe_layer(d);
  std::filesystem::remove_all(dir);
}
