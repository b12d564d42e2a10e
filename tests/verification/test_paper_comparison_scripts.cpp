// The reproduction tooling (docs/results.md) on a real run: a reduced paper scene (the
// paper's cells, physics and columnar layer on 40 mm, bands moved onto it) run by the CLI,
// then analysis/paper_compare.py and analysis/paper_results.py on its folder. Checked: the
// shock where the Rankine-Hugoniot speed puts it, the columnar layer's undisturbed top at
// exactly y = 0, the Python lifting delay equal to the C++ rule of the sweep summary
// (insitu/lifting_delay.cpp via summarise_run) on the same profile, band peaks present and
// of the right sign, and the results table written with its verdict column.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "solver/app/run_summary.hpp"
#include "solver/scene/scene.hpp"
#include "support/run_cli.hpp"

namespace dustlift {
namespace {

namespace fs = std::filesystem;

/// (exit status, stdout + stderr) of a shell command.
std::pair<int, std::string> run(const std::string& command) {
  const testing::CliResult r = testing::run_command(command);
  return {r.exit_code, r.output};
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The number after "key": in a JSON text (NaN -> NaN).
double json_number(const std::string& json, const std::string& key) {
  const std::regex re("\"" + key + "\": (-?[0-9.eE+-]+|NaN)");
  std::smatch m;
  if (!std::regex_search(json, m, re)) return -1e300;
  return m[1] == "NaN" ? std::nan("") : std::stod(m[1]);
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

TEST(PaperComparisonScripts, MeasureAReducedPaperRunAsTheCodeDefinesIt) {
  const fs::path dir = testing::fresh_dir("paper_compare");
  fs::create_directories(dir / "runs");
  // The paper scene with its bands moved onto a 40 mm layer.
  std::string scene = read_file(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/paper/vertical_shock.toml");
  replace_all(scene, "x_min = 0.100", "x_min = 0.010");
  replace_all(scene, "x_max = 0.200", "x_max = 0.030");
  const fs::path scene_path = dir / "reduced_paper.toml";
  std::ofstream(scene_path) << scene;
  const fs::path out = dir / "runs" / "paper";
  const std::string sets =
      " --set grid.x.start=-0.02 --set grid.x.end=0.04 --set grid.x.cells_below=20 --set particles.layer.x_max=0.04"
      " --set grid.y.end=0.012 --set grid.y.uniform_end=0.008 --set grid.y.cells_above=8"
      " --set initial.position=-0.001 --set run.end_time=6e-5 --set output.interval=2e-5";
  const auto [status, log] = run(std::string(DUSTLIFT_BINARY) + " run " + scene_path.string() + sets + " --out " +
                                 out.string() + " --threads 2");
  ASSERT_EQ(status, 0) << log;

  const std::string python = "/usr/bin/python3 " + std::string(DUSTLIFT_SOURCE_DIR) + "/analysis/";
  const fs::path json_path = dir / "compare.json";
  const auto [cstatus, coutput] =
      run(python + "paper_compare.py " + out.string() + " --time 6e-5 --json " + json_path.string());
  ASSERT_EQ(cstatus, 0) << coutput;
  const std::string json = read_file(json_path);

  // Shock: x0 + W t with W = 500.7 m/s (thermally perfect air, docs/gas-solver.md).
  EXPECT_NEAR(json_number(json, "shock_x_mm"), -1.0 + 500.7e3 * 6e-5, 2.0) << json;
  // Columnar layer: the undisturbed top is the layer top, y = 0, to round-off.
  EXPECT_NEAR(json_number(json, "layer_top_mm"), 0.0, 1e-9);
  // The raw-column delay is the C++ rule on the same profile (threshold 0.1 mm).
  const Scene resolved = load_scene((out / "scene.resolved.toml").string());
  const RunResults cpp = summarise_run(out.string(), resolved, {}, 1e-4);
  const double py_delay = json_number(json, "lifting_delay_raw_mm");
  if (std::isnan(cpp.lifting_delay)) {
    EXPECT_TRUE(std::isnan(py_delay)) << json;
  } else {
    EXPECT_NEAR(py_delay, cpp.lifting_delay * 1e3, 1e-6) << json;
  }
  // The delay at other thresholds (its sensitivity): the same rule, so the 0.1 mm entry is
  // the delay itself, and a higher threshold is never crossed nearer the shock.
  const double d005 = json_number(json, "0.05 mm"), d01 = json_number(json, "0.1 mm"),
               d02 = json_number(json, "0.2 mm"), delay = json_number(json, "lifting_delay_mm");
  ASSERT_TRUE(std::isnan(d01) || d01 > -1e300) << "lifting_delay_by_threshold_mm missing: " << json;
  if (std::isnan(delay)) {
    EXPECT_TRUE(std::isnan(d01)) << json;
  } else {
    EXPECT_EQ(d01, delay) << json;
    if (!std::isnan(d005)) {
      EXPECT_LE(d005, d01) << json;
    }
    if (!std::isnan(d02)) {
      EXPECT_LE(d01, d02) << json;
    }
  }
  // The first upward contact comes no later and is no larger than the largest one.
  const double first_up = json_number(json, "contact_first_up_10us_uN");
  const double largest_up = json_number(json, "contact_up_10us_uN");
  ASSERT_TRUE(std::isnan(first_up) || first_up > -1e300) << json;
  if (!std::isnan(first_up)) {
    EXPECT_GT(first_up, 0.0) << json;
    EXPECT_LE(first_up, largest_up) << json;
    EXPECT_LE(json_number(json, "contact_first_up_10us_tau_us"), json_number(json, "contact_up_10us_tau_us")) << json;
  }
  // Band forces: the shock pushes the surface band down (drag, pressure < 0, larger in the
  // 1 us bins than in the 0.01 ms means) and the floor pushes back (contact > 0).
  const double drag_1us = json_number(json, "drag_down_1us_uN"), drag_10us = json_number(json, "drag_down_10us_uN");
  EXPECT_LT(drag_10us, 0.0) << json;
  EXPECT_LE(drag_1us, drag_10us) << json;
  EXPECT_LT(json_number(json, "pressure_down_10us_uN"), 0.0) << json;
  EXPECT_GT(json_number(json, "contact_up_10us_uN"), 0.0) << json;

  // The results table from a folder holding that run as "paper".
  const fs::path docs = dir / "docs";
  const auto [rstatus, routput] = run(python + "paper_results.py " + (dir / "runs").string() + " --docs " + docs.string());
  ASSERT_EQ(rstatus, 0) << routput;
  const std::string numbers = read_file(docs / "numbers.md");
  EXPECT_NE(numbers.find("| shock position at 0.6 ms | 290 mm |"), std::string::npos) << numbers;
  EXPECT_NE(numbers.find("not run"), std::string::npos) << numbers;  // the studies are missing
  for (const char* png : {"fig5.png", "fig6.png", "fig7.png", "packing.png", "fig10.png",
                          "fig12.png", "loosetop.png"})
    EXPECT_TRUE(fs::exists(docs / png)) << png;
  fs::remove_all(dir);
}

TEST(PaperComparisonScripts, LooseTopLayerIsMeasuredFromItsColumnsTopByBothRules) {
  // The reduced paper scene with its top two rows half filled (docs/dem.md, "A looser top"):
  // the t = 0 surface reads the half-filled top cell 0.1 mm below the columns' top; both the
  // Python comparison and the C++ sweep summary measure lifting from the columns' top, y = 0.
  const fs::path dir = testing::fresh_dir("paper_compare_loose");
  std::string scene =
      read_file(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/paper/vertical_shock.toml");
  replace_all(scene, "x_min = 0.100", "x_min = 0.010");
  replace_all(scene, "x_max = 0.200", "x_max = 0.030");
  const fs::path scene_path = dir / "reduced_paper.toml";
  std::ofstream(scene_path) << scene;
  const fs::path out = dir / "loosetop";
  const std::string sets =
      " --set grid.x.start=-0.02 --set grid.x.end=0.04 --set grid.x.cells_below=20 --set "
      "particles.layer.x_max=0.04"
      " --set grid.y.end=0.012 --set grid.y.uniform_end=0.008 --set grid.y.cells_above=8"
      " --set initial.position=-0.001 --set run.end_time=4e-5 --set output.interval=2e-5"
      " --set particles.layer.loose_top_rows=2 --set particles.layer.loose_top_fill=0.5";
  const auto [status, log] = run(std::string(DUSTLIFT_BINARY) + " run " + scene_path.string() +
                                 sets + " --out " + out.string() + " --threads 2");
  ASSERT_EQ(status, 0) << log;
  EXPECT_NE(log.find("loose top: the top 2 rows at fill 0.5, 5720 parcels placed"),
            std::string::npos)
      << log << " (20 rows x 301 columns, 150 sites left out in each of the top two)";
  const fs::path json_path = dir / "compare.json";
  const auto [cstatus, coutput] =
      run("/usr/bin/python3 " + std::string(DUSTLIFT_SOURCE_DIR) + "/analysis/paper_compare.py " +
          out.string() + " --time 4e-5 --json " + json_path.string());
  ASSERT_EQ(cstatus, 0) << coutput;
  const std::string json = read_file(json_path);
  EXPECT_NEAR(json_number(json, "surface_at_t0_mm"), -0.1, 0.01) << json;
  EXPECT_EQ(json_number(json, "layer_top_mm"), 0.0) << json;
  const Scene resolved = load_scene((out / "scene.resolved.toml").string());
  const RunResults cpp = summarise_run(out.string(), resolved, {}, 1e-4);
  EXPECT_EQ(cpp.layer_top, 0.0);
  const double py_delay = json_number(json, "lifting_delay_raw_mm");
  if (std::isnan(cpp.lifting_delay)) {
    EXPECT_TRUE(std::isnan(py_delay)) << json;
  } else {
    EXPECT_NEAR(py_delay, cpp.lifting_delay * 1e3, 1e-6) << json;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dustlift
