// Layer files (`arrangement = "file"`, docs/dem.md): the CSV reader's happy path, the real
// particles per parcel it derives, and every bad file through the CLI (exit 2, one line
// "file:line:column: ...", no output folder).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "solver/dem/coarse_graining.hpp"
#include "solver/scene/parcel_file.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"
#include "support/run_cli.hpp"

namespace fs = std::filesystem;
using namespace dustlift;
using dustlift::testing::expect_bad_input;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_cli;
using dustlift::testing::write_file;

namespace {

const ParcelFileLimits kLimits{0.0, 0.004, 0.0, 0.002, 100e-6, 500e-6};
const PlacedParcel kDefaults{0.0, 0.0, 100e-6, 0.0, 0.0, 0.0, 300.0};

/// 8 x 4 cells of 0.5 mm, layer rectangle the lower half; the layer comes from layer.csv.
const std::string kScene = R"([run]
end_time = 2e-6
[grid]
x = { start = 0.0, end = 0.004, cells = 8 }
y = { start = 0.0, end = 0.002, cells = 4 }
[initial]
kind = "uniform"
state = { p = 101325.0, T = 300.0 }
[particles]
diameter = 100e-6
density = 980.0
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
x_min = 0.0
x_max = 0.004
y_min = 0.0
y_max = 0.001
arrangement = "file"
file = "layer.csv"
[output]
vtk = false
)";

std::string error_of(const std::string& text) {
  try {
    parse_parcel_file(text, "layer.csv", kDefaults, kLimits);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(LayerFile, ParsesCommentsBlanksSpacesCrlfAndColumnsInAnyOrder) {
  const std::string text =
      "# two parcels for a head-on impact\n"
      "\n"
      "vy, x ,y,diameter,omega,temperature,vx\r\n"
      "  0 , 0.001, 0.0005 , 120e-6, 5, 310, 1.5\r\n"
      "# between parcels\n"
      "-2.5,+2.0e-3,1e-3,1e-4,0,300,-1\n";
  const auto p = parse_parcel_file(text, "layer.csv", kDefaults, kLimits);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].x, 0.001);
  EXPECT_EQ(p[0].y, 0.0005);
  EXPECT_EQ(p[0].diameter, 120e-6);
  EXPECT_EQ(p[0].vx, 1.5);
  EXPECT_EQ(p[0].vy, 0.0);
  EXPECT_EQ(p[0].omega, 5.0);
  EXPECT_EQ(p[0].temperature, 310.0);
  EXPECT_EQ(p[1].x, 2e-3);
  EXPECT_EQ(p[1].vx, -1.0);
  EXPECT_EQ(p[1].vy, -2.5);
}

TEST(LayerFile, AbsentColumnsTakeTheSceneDefaults) {
  const auto p = parse_parcel_file("x,y\n0.001,0.001\n", "layer.csv", kDefaults, kLimits);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].diameter, 100e-6);
  EXPECT_EQ(p[0].vx, 0.0);
  EXPECT_EQ(p[0].omega, 0.0);
  EXPECT_EQ(p[0].temperature, 300.0);
}

TEST(LayerFile, ErrorsNameLineAndColumn) {
  // The column counts characters from 1 at the start of the offending field.
  EXPECT_EQ(error_of("x,y\n0.001,abc\n"), "layer.csv:2:7: column 'y': 'abc' is not a finite number");
  EXPECT_EQ(error_of("x, y\n0.001, nan\n"), "layer.csv:2:8: column 'y': 'nan' is not a finite number");
  EXPECT_EQ(error_of("x,y,mass\n"),
            "layer.csv:1:5: unknown column 'mass' (known: x, y, diameter, vx, vy, omega, "
            "temperature, particle_diameter)");
  EXPECT_EQ(error_of("x,y,x\n"), "layer.csv:1:5: column 'x' appears twice");
  EXPECT_EQ(error_of("# c\nx,diameter\n"), "layer.csv:2:1: missing column 'y' (x and y are required)");
  EXPECT_EQ(error_of("x,y\n0.001,0.001,5\n"), "layer.csv:2:13: expected 2 fields as in the header (line 1), found 3");
  EXPECT_EQ(error_of("x,y,vx\n0.001,0.001\n"), "layer.csv:2:12: expected 3 fields as in the header (line 1), found 2");
  EXPECT_EQ(error_of("x,y,diameter\n0.001,0.001,0\n"), "layer.csv:2:13: column 'diameter': must be > 0");
  EXPECT_EQ(error_of("x,y,diameter\n0.001,0.001,-1e-4\n"), "layer.csv:2:13: column 'diameter': must be > 0");
  EXPECT_EQ(error_of("x,y,temperature\n0.001,0.001,0\n"), "layer.csv:2:13: column 'temperature': must be > 0");
  EXPECT_EQ(error_of("x,y\n0.005,0.001\n"),
            "layer.csv:2:1: column 'x': parcel centre outside the grid (x from 0 to 0.004 m)");
  EXPECT_EQ(error_of("x,y\n0.001,-1e-9\n"),
            "layer.csv:2:7: column 'y': parcel centre outside the grid (y from 0 to 0.002 m)");
  EXPECT_NE(error_of("x,y,diameter\n0.001,0.001,5e-5\n").find("layer.csv:2:13: column 'diameter': smaller than"),
            std::string::npos);
  EXPECT_NE(error_of("x,y,diameter\n0.001,0.001,6e-4\n").find("layer.csv:2:13: column 'diameter': larger than"),
            std::string::npos);
  EXPECT_EQ(error_of("# only a comment\n\n"), "layer.csv:1:1: no header line (column names, e.g. x,y,diameter)");
  EXPECT_EQ(error_of("\n# c\nx,y\n"), "layer.csv:3:1: no parcel after the header");
}

TEST(LayerFile, SceneReadsTheFileBesideItAndDerivesRealParticlesPerParcel) {
  const auto dir = fresh_dir("layer_file_scene");
  write_file(dir / "layer.csv", "x,y,diameter\n0.001,0.0005,100e-6\n0.002,0.0005,200e-6\n");
  write_file(dir / "scene.toml", kScene);
  const Scene s = load_scene((dir / "scene.toml").string());
  const DemConfig& d = s.particles;
  ASSERT_EQ(d.layer_parcels.size(), 2u);
  EXPECT_EQ(d.layer_parcels[1].diameter, 200e-6);
  // No volume_fraction: each parcel's disc holds the plane's fraction, (pi D^2/4) / V_p.
  EXPECT_NEAR(d.real_per_parcel, equal_fraction_real_per_parcel(100e-6, 100e-6), 1e-9);
  EXPECT_NEAR(d.real_per_parcel, 15000.0, 1e-9);
  // The resolved scene names the file by its absolute path and reads back to the same parcels.
  const std::string absolute = fs::absolute(dir / "layer.csv").lexically_normal().string();
  EXPECT_NE(s.resolved_toml.find(absolute), std::string::npos) << s.resolved_toml;
  const Scene again = parse_scene(s.resolved_toml, "/elsewhere/resolved.toml");
  ASSERT_EQ(again.particles.layer_parcels.size(), 2u);
  EXPECT_EQ(again.particles.layer_parcels[1].x, 0.002);
  EXPECT_EQ(again.particles.real_per_parcel, d.real_per_parcel);

  // With volume_fraction the layer rectangle (4 mm x 1 mm) holds that fraction in 3-D: the
  // 200 um parcel counts as 4 parcels of parcel_diameter (n ~ D^2, eq. 11).
  const Scene f = load_scene((dir / "scene.toml").string(), {"particles.layer.volume_fraction=0.01"});
  const double n_ref = f.particles.real_per_parcel;
  EXPECT_NEAR(volume_fraction_3d(1.0 + 4.0, n_ref, 100e-6, 0.004 * 0.001), 0.01, 1e-14);
  fs::remove_all(dir);
}

TEST(LayerFile, KeysOfGeneratedLayersAreRefusedWithAFileAndTheFileWithoutOne) {
  const auto dir = fresh_dir("layer_file_keys");
  write_file(dir / "layer.csv", "x,y\n0.001,0.0005\n");
  write_file(dir / "scene.toml", kScene);
  auto message = [&](const std::vector<std::string>& overrides) {
    try {
      load_scene((dir / "scene.toml").string(), overrides);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({"particles.layer.seed=3"}).find("key 'particles.layer.seed': not used with arrangement = \"file\""),
            std::string::npos);
  EXPECT_NE(message({"particles.layer.loose_top_rows=2"})
                .find("key 'particles.layer.loose_top_rows': not used with arrangement = \"file\""),
            std::string::npos);
  EXPECT_NE(message({"particles.layer.arrangement=columnar"}).find("key 'particles.layer.file': only used with"),
            std::string::npos);
  EXPECT_NE(message({"particles.layer.arrangement=cubic"}).find("\"cubic\" is not one of \"jittered_lattice\""),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(LayerFile, BadFilesThroughTheCliExitWith2NamingFileLineAndColumnAndWriteNothing) {
  struct Case {
    const char* name;
    const char* csv;        ///< nullptr: no file at all
    const char* named;
  };
  const Case cases[] = {
      {"missing_column", "x,diameter\n0.001,1e-4\n", "layer.csv:1:1: missing column 'y'"},
      {"unknown_column", "x,y,speed\n", "layer.csv:1:5: unknown column 'speed'"},
      {"not_a_number", "x,y\n0.001,0.5e-3\n0.002,one\n", "layer.csv:3:7: column 'y': 'one' is not a finite number"},
      {"too_many_fields", "x,y\n0.001,0.0005,0\n", "layer.csv:2:14: expected 2 fields"},
      {"too_few_fields", "x,y,vx\n0.001,0.0005\n", "layer.csv:2:13: expected 3 fields"},
      {"outside_grid", "x,y\n0.001,0.0025\n", "layer.csv:2:7: column 'y': parcel centre outside the grid"},
      {"zero_diameter", "x,y,diameter\n0.001,0.0005,0.0\n", "layer.csv:2:14: column 'diameter': must be > 0"},
      {"negative_diameter", "x,y,diameter\n0.001,0.0005,-1e-4\n", "layer.csv:2:14: column 'diameter': must be > 0"},
      {"no_parcels", "# header only\nx,y\n", "layer.csv:2:1: no parcel after the header"},
      {"no_file", nullptr, "layer.csv: cannot open layer file"},
  };
  {
    // A device is refused before it is read (reading /dev/zero would never end).
    const auto dir = fresh_dir("layer_file_cli_device");
    write_file(dir / "scene.toml", kScene);
    const fs::path out = dir / "out";
    const auto r = run_cli("run " + (dir / "scene.toml").string() + " --out " + out.string() +
                           " --set particles.layer.file=/dev/zero");
    expect_bad_input(r, "/dev/zero: is not a regular file, not a layer file", out, "device");
    fs::remove_all(dir);
  }
  for (const Case& c : cases) {
    const auto dir = fresh_dir(std::string("layer_file_cli_") + c.name);
    write_file(dir / "scene.toml", kScene);
    if (c.csv != nullptr) write_file(dir / "layer.csv", c.csv);
    const fs::path out = dir / "out";
    const auto r = run_cli("run " + (dir / "scene.toml").string() + " --out " + out.string());
    expect_bad_input(r, c.named, out, c.name);
    fs::remove_all(dir);
  }
}
