// The bad-input table (docs/reliability.md) through the CLI binary: every row must exit with
// code 2, print exactly one line that names the problem (key, file or folder), and leave no
// output folder behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "support/run_cli.hpp"

namespace fs = std::filesystem;
using dustlift::testing::CliResult;
using dustlift::testing::expect_bad_input;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_cli;
using dustlift::testing::write_file;

namespace {

/// A small valid coupled scene: 0.5 mm cells, 0.1 mm parcels in a 1 mm layer.
const char* kScene = R"([run]
end_time = 2e-6
[grid]
x = { start = 0.0, end = 0.004, cells = 8 }
y = { start = 0.0, end = 0.002, cells = 4 }
[boundary]
left = "periodic"
right = "periodic"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "uniform"
state = { p = 101325.0, T = 300.0, u = 10.0 }
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
volume_fraction = 0.4
[output]
vtk = false
)";

struct Row {
  const char* name;
  std::string scene;      ///< file content ("" = the valid scene)
  const char* arguments;  ///< extra CLI arguments; {scene}, {dir} are substituted
  const char* named;      ///< what the one-line message must name
};

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

std::string without_line(const std::string& text, const std::string& line) {
  return replace_all(text, line + "\n", "");
}

class BadInput : public ::testing::TestWithParam<Row> {};

}  // namespace

TEST_P(BadInput, ExitsWith2OneLineNamingTheProblemAndWritesNothing) {
  const Row& row = GetParam();
  const auto dir = fresh_dir(std::string("badin_") + row.name);
  const fs::path scene = dir / "scene.toml";
  write_file(scene, row.scene.empty() ? kScene : row.scene);
  const fs::path out = dir / "out";
  std::string args =
      replace_all(replace_all(row.arguments, "{scene}", scene.string()), "{dir}", dir.string());
  if (args.find("--out") == std::string::npos) args += " --out " + out.string();
  const CliResult r = run_cli("run " + args);
  expect_bad_input(r, row.named, out, row.name);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Table, BadInput,
    ::testing::Values(
        Row{"missing_end_time", without_line(kScene, "end_time = 2e-6"), "{scene}", "run.end_time"},
        Row{"missing_grid",
            replace_all(without_line(kScene, "x = { start = 0.0, end = 0.004, cells = 8 }"),
                        "y = { start = 0.0, end = 0.002, cells = 4 }\n", ""),
            "{scene}", "grid.x"},
        Row{"missing_cells", "", "{scene} --set grid.x={start=0.0,end=0.004}", "grid.x.cells"},
        Row{"wrong_type_number", "", "{scene} --set run.end_time=\\\"soon\\\"", "run.end_time"},
        Row{"wrong_type_bool", "", "{scene} --set coupling.drag=3", "coupling.drag"},
        Row{"wrong_type_table", "", "{scene} --set particles.layer=5", "particles.layer"},
        Row{"zero_cells", "", "{scene} --set grid.y.cells=0", "grid.y.cells"},
        Row{"negative_cells", "", "{scene} --set grid.x.cells=-8", "grid.x.cells"},
        Row{"too_many_cells", "", "{scene} --set grid.x.cells=2000000", "grid.x.cells"},
        Row{"cell_size_typo", "", "{scene} --set grid.x={start=0.0,end=0.004,cell_size=2.5e-14}",
            "grid.x.cell_size"},
        Row{"inverted_axis", "", "{scene} --set grid.x.end=-0.004", "grid.x.end"},
        Row{"negative_diameter", "", "{scene} --set particles.diameter=-1e-4",
            "particles.diameter"},
        Row{"zero_parcel_diameter", "", "{scene} --set particles.parcel_diameter=0",
            "particles.parcel_diameter"},
        Row{"negative_density", "", "{scene} --set particles.density=-980", "particles.density"},
        Row{"alpha_p_0_9", "", "{scene} --set particles.layer.volume_fraction=0.9",
            "particles.layer.volume_fraction"},
        Row{"alpha_p_above", "", "{scene} --set particles.layer.volume_fraction=0.95",
            "particles.layer.volume_fraction"},
        Row{"parcel_larger_than_cell", "", "{scene} --set particles.parcel_diameter=6e-4",
            "particles.parcel_diameter"},
        Row{"zero_end_time", "", "{scene} --set run.end_time=0", "run.end_time"},
        Row{"negative_end_time", "", "{scene} --set run.end_time=-1e-3", "run.end_time"},
        Row{"negative_checkpoint_interval", "", "{scene} --set output.checkpoint_interval=-1",
            "output.checkpoint_interval"},
        Row{"toml_syntax", "[run\nend_time = 1\n", "{scene}", "TOML syntax error"},
        Row{"unknown_key", "", "{scene} --set run.speed=2", "run.speed"},
        Row{"scene_is_a_folder", "", "{dir}", "is a folder"},
        Row{"scene_in_missing_folder", "", "{dir}/no/such/scene.toml", "cannot open"},
        Row{"output_under_a_file", "", "{scene} --out {scene}/out", "output folder"},
        Row{"output_is_a_file", "", "{scene} --out {scene}", "output folder"},
        Row{"scene_and_restart", "", "{scene} --restart {scene}",
            "either a scene file or --restart"},
        Row{"restart_is_a_folder", "", "--restart {dir}", "is a folder"},
        Row{"restart_missing", "", "--restart {dir}/none.h5", "cannot open"},
        Row{"restart_foreign", "", "--restart {scene}", "not a dustlift checkpoint"},
        // A typo of a required key is an unknown key (with the key meant), not a missing one.
        Row{"typo_of_required_key", replace_all(kScene, "end_time = 2e-6", "end_tme = 2e-6"),
            "{scene}", "key 'run.end_tme': unknown key (did you mean 'run.end_time'?)"},
        // A bad --set value is named by the override, not by a line of the scene file.
        Row{"override_named", "", "{scene} --set particles.layer.volume_fraction=0.95",
            "--set 'particles.layer.volume_fraction=0.95': key 'particles.layer.volume_fraction'"},
        Row{"override_typo", "", "{scene} --set initial.stat.p=1e5",
            "--set 'initial.stat.p=1e5': key 'initial.stat': unknown key (did you mean "
            "'initial.state'?)"},
        // A unit slip: a pressure in atm, a temperature in degrees Celsius (the file, line, key and
        // unit named).
        Row{"pressure_in_atm", replace_all(kScene, "p = 101325.0", "p = 1.0"), "{scene}",
            "scene.toml:13: key 'initial.state.p': 1 Pa is below 1 kPa"},
        Row{"temperature_in_celsius", replace_all(kScene, "T = 300.0", "T = 27.0"), "{scene}",
            "key 'initial.state.T': 27 K is below 100 K, implausible for a temperature: "
            "temperatures are in K (did you "
            "mean 27 degC = 300.15 K?)"},
        // The layer's thickness and a floor that contradicts it (the floor is read first).
        Row{"thickness_and_floor", "", "{scene} --set particles.layer.thickness=2e-3",
            "key 'grid.y.start': 0 m contradicts particles.layer.thickness = 0.002 m"},
        Row{"thickness_and_y_min", "",
            "{scene} --set particles.layer.thickness=1e-3 --set "
            "grid.y={start=0.0,end=0.002,cells=4} --set particles.layer.y_min=0.0005",
            "key 'particles.layer.y_min': 0.0005 m contradicts particles.layer.thickness = 0.001 "
            "m"}),
    [](const auto& info) { return std::string(info.param.name); });

// Inputs a machine cannot run, or values no run needs: refused before anything is allocated
// (a grid of 10^12 cells used to abort with std::bad_alloc, exit 134, leaving a folder).
INSTANTIATE_TEST_SUITE_P(
    Oversized, BadInput,
    ::testing::Values(
        Row{"grid_of_1e12_cells", "",
            "{scene} --set grid.x.cells=1000000 --set grid.y.cells=1000000", "grid.x.cells"},
        Row{"grid_of_1e10_cells", "", "{scene} --set grid.x.cells=100000 --set grid.y.cells=100000",
            "grid.x.cells"},
        Row{"stretched_grid_of_1e12_cells", "",
            "{scene} --set grid.x={start=0.0,end=1.0,cell_size=1e-6} --set "
            "grid.y={start=0.0,end=1.0,cell_size=1e-6}",
            "grid.x.cell_size"},
        Row{"parcels_of_10_nm", "", "{scene} --set particles.diameter=1e-8",
            "key 'particles.diameter': 1e-08 m parcels fill the layer"},
        Row{"coarse_parcels_of_20_nm", "",
            "{scene} --set particles.diameter=1e-8 --set particles.parcel_diameter=2e-8",
            "particles.parcel_diameter"},
        Row{"cfl_1e_320", "", "{scene} --set gas.scheme.cfl=1e-320", "gas.scheme.cfl"},
        Row{"dem_courant_1e_9", "", "{scene} --set particles.courant=1e-9", "particles.courant"},
        Row{"gas_at_20000_K", "", "{scene} --set \"initial.state={ p = 1e5, T = 20000.0 }\"",
            "initial.state.T"},
        Row{"gas_at_50_K", "", "{scene} --set \"initial.state={ p = 1e5, T = 50.0 }\"",
            "initial.state.T"},
        Row{"shock_beyond_the_fits", "",
            "{scene} --set initial.kind=shock --set initial.mach=30 --set initial.position=0.001",
            "initial.mach"},
        Row{"probe_outside_the_grid", "",
            "{scene} --set \"output.probes=[{ name = \\\"gauge\\\", x = 0.5, y = 0.001 }]\"",
            "output.probes[0].x"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(BadInput, RestartRowsNeedingARealCheckpoint) {
  const auto dir = fresh_dir("badin_restart");
  write_file(dir / "scene.toml", kScene);
  const CliResult made = run_cli("run " + (dir / "scene.toml").string() + " --out " +
                                 (dir / "first").string() + " --threads 1 --set run.max_steps=2");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const fs::path checkpoint = dir / "first" / "checkpoint.h5";
  ASSERT_TRUE(fs::exists(checkpoint));

  // End time not after the checkpoint's time (the checkpoint was taken after 2 steps).
  fs::path out = dir / "out_end";
  CliResult r = run_cli("run --restart " + checkpoint.string() + " --out " + out.string() +
                        " --set run.end_time=1e-12");
  expect_bad_input(r, "run.end_time", out, "restart_end_before_checkpoint");

  // Physics keys may not change on restart.
  out = dir / "out_physics";
  r = run_cli("run --restart " + checkpoint.string() + " --out " + out.string() +
              " --set grid.x.cells=16");
  expect_bad_input(r, "grid.x.cells", out, "restart_changes_physics");

  // A restart into another folder that holds files (here: a scene) must not mix them in.
  fs::create_directories(dir / "busy");
  write_file(dir / "busy" / "notes.txt", "mine");
  r = run_cli("run --restart " + checkpoint.string() + " --out " + (dir / "busy").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("output folder '" + (dir / "busy").string() + "': not empty"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "busy"), fs::directory_iterator()), 1);

  // Truncated copy.
  std::string bytes;
  {
    std::ifstream in(checkpoint, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  write_file(dir / "truncated.h5", bytes.substr(0, bytes.size() / 2));
  out = dir / "out_truncated";
  r = run_cli("run --restart " + (dir / "truncated.h5").string() + " --out " + out.string());
  expect_bad_input(r, "truncated", out, "restart_truncated");
  fs::remove_all(dir);
}
