// The [particles] scene section: defaults are the paper's, errors name the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

Scene parse(const std::string& particles) { return parse_scene(kBase + particles, "test.toml"); }

/// The SceneError message of parsing `particles`, or "" if it parsed.
std::string error_of(const std::string& particles) {
  try {
    parse(particles);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SceneParticles, AbsentSectionDisablesParcels) {
  const Scene s = parse("");
  EXPECT_FALSE(s.particles.enabled);
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
