// `dustlift sweep` (solver/app/sweep.hpp): the --vary syntax, run folders, study files, and
// whole sweeps through the CLI on scenes that take a fraction of a second per run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "insitu/series_table.hpp"
#include "solver/app/sweep.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"
#include "support/run_cli.hpp"

namespace fs = std::filesystem;
using namespace dustlift;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_cli;
using dustlift::testing::write_file;

namespace {

/// Mach 1.44 shock from x = -2 mm over a 16 mm x 1 mm layer, 0.5 mm cells, 20 us (~90 steps).
const char* kTinyShockScene = R"([run]
end_time = 20e-6
[grid]
x = { start = -0.004, end = 0.016, cells = 40 }
y = { start = -0.001, end = 0.005, cells = 12 }
[gas]
thermo = "calorically_perfect"
[gas.transport]
model = "inviscid"
[boundary]
left = "inflow"
right = "outflow"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "shock"
mach = 1.44
position = -0.002
state = { p = 101.0e3, T = 300.0 }
[particles]
diameter = 100e-6
density = 980.0
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
x_min = 0.0
x_max = 0.016
y_min = -0.001
y_max = 0.0
[output]
interval = 5e-6
vtk = false
)";

/// CSV rows (header first) as fields; quoted fields keep their commas.
std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        fields.emplace_back();
      } else {
        fields.back() += c;
      }
    }
    rows.push_back(fields);
  }
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return k;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

}  // namespace

TEST(Sweep, ValueListsSplitOutsideBracketsAndQuotes) {
  EXPECT_EQ(split_value_list("1e-4, 3e-4,5e-4"), (std::vector<std::string>{"1e-4", "3e-4", "5e-4"}));
  EXPECT_EQ(split_value_list("{ p = 1, T = 2 },{ p = 3, T = 4 }"),
            (std::vector<std::string>{"{ p = 1, T = 2 }", "{ p = 3, T = 4 }"}));
  EXPECT_EQ(split_value_list("[1, 2],\"a,b\",columnar"), (std::vector<std::string>{"[1, 2]", "\"a,b\"", "columnar"}));
}

TEST(Sweep, VaryAxesZipKeysJoinedBySemicolonsAndRejectMismatches) {
  const SweepAxis a = parse_vary("grid.x.cell_size=1e-3,5e-4;grid.y.cells_above=6,12");
  ASSERT_EQ(a.keys, (std::vector<std::string>{"grid.x.cell_size", "grid.y.cells_above"}));
  EXPECT_EQ(a.size(), 2u);
  EXPECT_EQ(a.values[1][1], "12");
  EXPECT_THROW(parse_vary("a=1,2;b=1"), SceneError);
  EXPECT_THROW(parse_vary("=1,2"), SceneError);
  EXPECT_THROW(parse_vary("a=1,,2"), SceneError);
  EXPECT_THROW(parse_vary("novalues"), SceneError);
}

TEST(Sweep, RunsAreEveryCombinationWithSafeUniqueFolderNames) {
  SweepDefinition d;
  d.axes = {parse_vary("coupling.magnus_coefficient=0,1"), parse_vary("initial.state={ p = 1e5, T = 300 },x/y")};
  const auto runs = sweep_runs(d);
  ASSERT_EQ(runs.size(), 4u);
  // The first axis varies slowest.
  EXPECT_EQ(runs[0].overrides[0].second, "0");
  EXPECT_EQ(runs[1].overrides[0].second, "0");
  EXPECT_EQ(runs[2].overrides[0].second, "1");
  EXPECT_EQ(runs[1].overrides[1].second, "x/y");
  EXPECT_EQ(runs[0].folder, "coupling.magnus_coefficient=0,initial.state=__p_=_1e5,_T_=_300__");
  EXPECT_EQ(runs[1].folder, "coupling.magnus_coefficient=0,initial.state=x_y");
  // Two values that sanitise alike still get their own folders.
  d.axes = {parse_vary("run.name=a/b,a_b")};
  const auto same = sweep_runs(d);
  EXPECT_EQ(same[0].folder, "run.name=a_b");
  EXPECT_EQ(same[1].folder, "run.name=a_b_2");
}

TEST(Sweep, StudyFileGivesSceneAxesOverridesAndStations) {
  const auto dir = fresh_dir("study_file");
  write_file(dir / "study.toml", R"(# a study
scene = "../cases/scene.toml"
stations = [0.05, 0.25]
lift_threshold = 0.5e-3
[set]
"coupling.magnus_coefficient" = 0.0
"particles.layer.arrangement" = "columnar"
[[vary]]
"particles.contact.damping" = [5e-5, 1.0e-4, 3e-4]
[[vary]]
"grid.x.cell_size" = [1e-3, 5e-4]
"grid.y.cell_size" = [1e-3, 5e-4]
)");
  const SweepDefinition d = read_study((dir / "study.toml").string());
  EXPECT_EQ(d.scene_path, (dir / "../cases/scene.toml").lexically_normal().string());
  EXPECT_EQ(d.stations, (std::vector<double>{0.05, 0.25}));
  EXPECT_EQ(d.lift_threshold, 0.5e-3);
  EXPECT_EQ(d.overrides, (std::vector<std::string>{"coupling.magnus_coefficient=0", "particles.layer.arrangement=columnar"}));
  ASSERT_EQ(d.axes.size(), 2u);
  EXPECT_EQ(d.axes[0].values[0], (std::vector<std::string>{"5e-05", "0.0001", "0.0003"}));
  EXPECT_EQ(d.axes[1].keys, (std::vector<std::string>{"grid.x.cell_size", "grid.y.cell_size"}));
  EXPECT_EQ(sweep_runs(d).size(), 6u);

  write_file(dir / "bad.toml", "scene = \"s.toml\"\n[[vary]]\n\"a\" = [1, 2]\n\"b\" = [1]\n");
  try {
    read_study((dir / "bad.toml").string());
    ADD_FAILURE() << "mismatched lists must be refused";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:4: key 'vary[0].b': 1 values, but 'a' has 2"), std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

TEST(Sweep, TwoByTwoSweepWritesFoldersSeriesSummaryAndPlot) {
  const auto dir = fresh_dir("sweep_2x2");
  write_file(dir / "tiny.toml", kTinyShockScene);
  const fs::path out = dir / "out";
  const auto r = run_cli("sweep " + (dir / "tiny.toml").string() +
                         " --vary particles.contact.damping=1e-4,3e-4 --vary particles.layer.arrangement=columnar,hexagonal"
                         " --stations 0.004,0.012 --threads 1 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const auto rows = read_csv(out / "summary.csv");
  ASSERT_EQ(rows.size(), 5u) << "header + 4 runs";
  const auto& h = rows[0];
  EXPECT_EQ(h[0], "run");
  EXPECT_EQ(h[1], "particles_contact_damping");  // the key, as an identifier
  EXPECT_EQ(h[2], "particles_layer_arrangement");
  const std::vector<std::string> damping{"1e-4", "1e-4", "3e-4", "3e-4"}, arrangement{"columnar", "hexagonal",
                                                                                         "columnar", "hexagonal"};
  // Mach 1.44 into 300 K air (gamma 1.4, R 288.19): W = 501.0 m/s; the 5 % foot leads by ~2 cells.
  const double shock_expected = -0.002 + 501.0 * 20e-6;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto& row = rows[k];
    SCOPED_TRACE(row[0]);
    EXPECT_EQ(row[1], damping[k - 1]);
    EXPECT_EQ(row[2], arrangement[k - 1]);
    EXPECT_EQ(row[column(h, "exit_status_1")], "0");
    const double wall = std::stod(row[column(h, "wall_time_s")]);
    EXPECT_TRUE(std::isfinite(wall) && wall > 0.0);
    EXPECT_GT(std::stod(row[column(h, "steps_1")]), 50.0);
    EXPECT_DOUBLE_EQ(std::stod(row[column(h, "end_time_s")]), 20e-6);
    EXPECT_NEAR(std::stod(row[column(h, "shock_x_m")]), shock_expected + 1e-3, 1e-3);
    // 20 us after the shock passed, no column of the layer has lifted 0.25 mm.
    EXPECT_EQ(row[column(h, "lifting_delay_m")], "nan");
    // The undisturbed top (median h at t = 0) is the layer top within 0.1 cell (50 um).
    EXPECT_NEAR(std::stod(row[column(h, "layer_top_m")]), 0.0, 0.05e-3);
    for (const char* station : {"h_at_x0p004_m", "h_at_x0p012_m"}) {
      EXPECT_NEAR(std::stod(row[column(h, station)]), 0.0, 0.05e-3) << station;
    }
    // The run's own folder: its series, and the resolved scene with the overrides.
    const fs::path run_dir = out / row[0];
    EXPECT_TRUE(fs::exists(run_dir / "series" / "surface_height.csv"));
    EXPECT_TRUE(fs::exists(run_dir / "series" / "forces_surface.csv"));
    EXPECT_TRUE(fs::exists(run_dir / "series" / "series.h5"));
    std::ifstream resolved(run_dir / "scene.resolved.toml");
    std::stringstream text;
    text << resolved.rdbuf();
    EXPECT_NE(text.str().find("arrangement = '" + arrangement[k - 1] + "'"), std::string::npos);
    // The summary's peak is the signed extreme of the band series (downward drag behind the shock).
    const auto forces = read_csv(run_dir / "series" / "forces_surface.csv");
    double extreme = 0.0, at = 0.0;
    const std::size_t drag = column(forces[0], "drag_y_N");
    for (std::size_t f = 1; f < forces.size(); ++f) {
      const double v = std::stod(forces[f][drag]);
      if (std::abs(v) > std::abs(extreme)) extreme = v, at = std::stod(forces[f][0]);
    }
    EXPECT_LT(extreme, 0.0);
    EXPECT_EQ(std::stod(row[column(h, "surface_drag_y_peak_N")]), extreme);
    EXPECT_EQ(std::stod(row[column(h, "surface_drag_y_peak_tau_s")]), at);
    // The cloud columns are the last row of the run's dust_cloud series.
    const auto cloud = read_csv(run_dir / "series" / "dust_cloud.csv");
    for (const auto& [summary, series] : std::vector<std::pair<std::string, std::string>>{
             {"cloud_lifted_mass_kg_per_m", "lifted_mass_kg_per_m"},
             {"cloud_lifted_share_1", "lifted_share_1"},
             {"cloud_height_p90_m", "height_p90_m"},
             {"cloud_top_m", "cloud_top_m"},
             {"cloud_explosible_area_m2", "explosible_area_m2"}})
      EXPECT_EQ(row[column(h, summary)], cloud.back()[column(cloud[0], series)]) << summary;
  }
  // The same rows in HDF5: numbers with units and the run names as strings.
  const std::string h5 = (out / "summary.h5").string();
  const SeriesTable numbers = read_series_h5(h5, "summary");
  EXPECT_EQ(numbers.rows(), 4u);
  EXPECT_EQ(numbers.header(2), "wall_time_s");
  const auto names = read_string_column_h5(h5, "summary", "run");
  ASSERT_EQ(names.size(), 4u);
  EXPECT_EQ(names[1], rows[2][0]);
  EXPECT_EQ(read_string_column_h5(h5, "summary", "particles_layer_arrangement")[3], "hexagonal");

  // One PNG overlaying the four h(x).
  const auto plot = dustlift::testing::run_command("/usr/bin/python3 " + std::string(DUSTLIFT_SOURCE_DIR) + "/analysis/plot_sweep.py " +
                                    out.string());
  EXPECT_EQ(plot.exit_code, 0) << plot.output;
  ASSERT_TRUE(fs::exists(out / "surface_height.png")) << plot.output;
  EXPECT_GT(fs::file_size(out / "surface_height.png"), 20000u);
  fs::remove_all(dir);
}

TEST(Sweep, AFailedRunIsRecordedAndTheSweepGoesOn) {
  // Sod with a second right state of 1e-30 density and pressure: that run blows up (exit 3,
  // as in Cli.NumericalFailureExitsWithCode3NamingStepCellAndVariable); the other finishes.
  const auto dir = fresh_dir("sweep_failure");
  const fs::path out = dir / "out";
  // The scene comes after the options here: each --set/--vary takes one value.
  const auto r = run_cli("sweep --threads 1 --set run.end_time=2e-4 --set \"initial.left={ rho = 1.0, p = 1e6 }\""
                         " --vary \"initial.right={ rho = 0.125, p = 0.1 },{ rho = 1e-30, p = 1e-30 }\" " +
                         std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/sod.toml --out " + out.string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  const auto rows = read_csv(out / "summary.csv");
  ASSERT_EQ(rows.size(), 3u) << r.output;
  const auto& h = rows[0];
  EXPECT_EQ(rows[1][column(h, "exit_status_1")], "0");
  EXPECT_EQ(rows[2][column(h, "exit_status_1")], "3");
  EXPECT_GT(std::stod(rows[2][column(h, "wall_time_s")]), 0.0);
  EXPECT_LT(std::stod(rows[2][column(h, "end_time_s")]), std::stod(rows[1][column(h, "end_time_s")]));
  EXPECT_EQ(rows[2][column(h, "shock_x_m")], "nan") << "a failed run's results are not reported";
  EXPECT_NE(rows[1][column(h, "shock_x_m")], "nan");
  std::ifstream log(out / rows[2][0] / "run.log");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_NE(text.str().find("numerical failure: step "), std::string::npos) << text.str();
  fs::remove_all(dir);
}

TEST(Sweep, ABadCombinationStopsTheSweepBeforeAnythingIsWritten) {
  const auto dir = fresh_dir("sweep_bad");
  write_file(dir / "tiny.toml", kTinyShockScene);
  const fs::path out = dir / "out";
  const auto r = run_cli("sweep " + (dir / "tiny.toml").string() + " --vary particles.contact.damping=1e-4,-1 --out " +
                         out.string());
  dustlift::testing::expect_bad_input(r, "key 'particles.contact.damping'", out, "negative damping");
  EXPECT_NE(r.output.find("sweep run 'particles.contact.damping=-1'"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(Sweep, EveryPaperStudyParsesForThePaperSceneAndItsProxy) {
  // cases/paper/studies/*.toml: each combination must be a valid scene with the study's own
  // scene and, for the studies that keep the grid, with the proxy the README runs them on
  // (the grid studies have *_proxy versions whose stretched parts fit the proxy).
  const fs::path studies = fs::path(DUSTLIFT_SOURCE_DIR) / "cases" / "paper" / "studies";
  const std::string proxy = (studies.parent_path() / "proxy.toml").string();
  int checked = 0, files = 0;
  for (const auto& entry : fs::directory_iterator(studies)) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    const SweepDefinition d = read_study(entry.path().string());
    const bool sets_grid = d.axes.front().keys.front().rfind("grid.", 0) == 0 ||
                           std::any_of(d.overrides.begin(), d.overrides.end(),
                                       [](const std::string& o) { return o.rfind("grid.", 0) == 0; });
    std::vector<std::string> scenes{d.scene_path};
    if (!sets_grid && fs::path(d.scene_path).filename() != "proxy.toml") scenes.push_back(proxy);
    for (const std::string& scene : scenes) {
      for (const SweepRun& run : sweep_runs(d)) {
        std::vector<std::string> overrides = d.overrides;
        for (const auto& [key, value] : run.overrides) overrides.push_back(key + "=" + value);
        EXPECT_NO_THROW(load_scene(scene, overrides)) << entry.path().filename() << " " << run.folder << " on " << scene;
        ++checked;
      }
    }
  }
  EXPECT_EQ(files, 10);
  // 5a 3, 5b 4, 5c 5, 6 4, particle diameter 3 on both scenes; 7a 3 and 7b 2 twice (paper, proxy files);
  // the loose top 3 x 3 on the proxy only.
  EXPECT_EQ(checked, 2 * (3 + 4 + 5 + 4 + 3) + 2 * (3 + 2) + 3 * 3);
}
