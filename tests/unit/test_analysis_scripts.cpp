// The analysis scripts run on files written by the C++ writers: make_figures.py on series
// (shock speed from the fit, one PNG per series family) and sod_compare.py on a .vtr.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>

#include "insitu/band_average.hpp"
#include "insitu/gas_cells.hpp"
#include "insitu/series_table.hpp"
#include "insitu/vtk_writers.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

namespace fs = std::filesystem;
const char* kPython = "/usr/bin/python3";

fs::path fresh_dir(const std::string& name) {
  return testing::scratch_dir("analysis_" + name);
}

/// Runs a command, returns (exit status, stdout + stderr).
std::pair<int, std::string> run(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  return {::pclose(pipe), output};
}

std::string script(const std::string& name) {
  return std::string(kPython) + " " + DUSTLIFT_SOURCE_DIR + "/analysis/" + name;
}

class AnalysisScripts : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kPython) ||
        run(std::string(kPython) + " -c 'import numpy, matplotlib'").first != 0)
      FAIL() << "/usr/bin/python3 with numpy and matplotlib is needed (scripts/install-deps.sh: "
                "python3-numpy python3-matplotlib)";
  }
};

TEST_F(AnalysisScripts, MakeFiguresFitsTheShockSpeedAndPlotsEverySeriesFamily) {
  const auto dir = fresh_dir("figures");
  SeriesSink sink(dir.string());
  SeriesTable shock("shock_position", {{"time", "s"}, {"x", "m"}});
  SeriesTable surface("surface_height", {{"time", "s"}, {"x", "m"}, {"height", "m"}});
  for (int k = 0; k < 8; ++k) {
    const double t = k * 2.5e-5;
    shock.append_row(std::vector{t, 0.05 + 500.9 * t});
    for (int i = 0; i < 20; ++i) surface.append_row(std::vector{t, 0.01 * i, 0.002 + 1e-4 * k * i});
    sink.write(shock);
    sink.write(surface);
  }
  std::vector<double> x0{0.01}, y0{0.001}, y{0.0012}, fx{0.1}, fy{0.2}, arrival{0.0}, w{5.0};
  BandForceSeries bands({Band{"top", 0.0, 0.1, 0.0, 0.002}});
  for (int k = 0; k < 5; ++k) {
    BandParcelsView v;
    v.count = 1;
    v.initial_position = {x0, y0};
    v.y = y;
    v.force_drag = {fx, fy};
    v.arrival_time = arrival;
    v.gas_rotation = w;
    bands.add(v, k * 1e-6);
  }
  bands.write(sink);
  const auto [status, output] = run(script("make_figures.py") + " " + dir.string());
  ASSERT_EQ(status, 0) << output;
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(output, m, std::regex("shock speed \\(linear fit\\): ([0-9.eE+-]+) m/s")))
      << output;
  EXPECT_NEAR(std::stod(m[1]), 500.9, 1e-6);
  for (const char* png :
       {"shock_position.png", "surface_height.png", "forces_top.png", "magnus_inputs_top.png"}) {
    EXPECT_TRUE(fs::exists(dir / "figures" / png)) << png << "\n" << output;
    if (fs::exists(dir / "figures" / png)) {
      EXPECT_GT(fs::file_size(dir / "figures" / png), 10000u) << png;
    }
  }
  fs::remove_all(dir);
}

TEST_F(AnalysisScripts, SodCompareReadsTheLastVtrAndMeasuresTheL1Error) {
  // Equal left and right states: the exact solution is the uniform state, so a file with
  // density raised by 0.01 everywhere has density L1 error 0.01 and the others 0.
  const auto dir = fresh_dir("sod");
  std::ofstream(dir / "scene.resolved.toml")
      << "[gas]\ngamma = 1.4\n[initial]\nkind = \"riemann\"\nposition = 0.5\n"
         "left = { rho = 1.0, p = 1.0, u = 0.0 }\nright = { rho = 1.0, p = 1.0, u = 0.0 }\n";
  GasCellArrays g;
  for (int i = 0; i <= 50; ++i) g.x_nodes.push_back(i / 50.0);
  g.y_nodes = {0.0, 0.01, 0.02, 0.03};
  g.resize(g.nx(), g.ny());
  VtkSeriesFiles files(dir.string(), "gas", "vtr");
  for (double t : {0.0, 0.1}) {
    for (std::size_t k = 0; k < g.cells(); ++k) {
      g.values("density")[k] = t > 0 ? 1.01 : 5.0;  // the t = 0 file must not be the one read
      g.values("pressure")[k] = 1.0;
    }
    write_gas_vtr(g, files.next_path(t));
    files.commit(t);
  }
  const auto [status, output] = run(script("sod_compare.py") + " " + dir.string());
  ASSERT_EQ(status, 0) << output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(output, m, std::regex("density +L1 error ([0-9.eE+-]+)")))
      << output;
  EXPECT_NEAR(std::stod(m[1]), 0.01, 1e-12);
  ASSERT_TRUE(std::regex_search(output, m, std::regex("pressure +L1 error ([0-9.eE+-]+)")))
      << output;
  EXPECT_LT(std::stod(m[1]), 1e-15);
  EXPECT_TRUE(fs::exists(dir / "figures" / "sod_compare.png"));
  fs::remove_all(dir);
}

TEST_F(AnalysisScripts, SummarizeRunPrintsTheReadmeLinesFromTheSeriesAndTheLastVtr) {
  // A synthetic run: shock at x = 0.05 + 500 t, a profile h(x) = 1e-3 x + 1e-4 t / 1e-5 with a
  // maximum at the last column, and one gas file.
  const auto dir = fresh_dir("summarize");
  SeriesSink sink(dir.string());
  SeriesTable shock("shock_position", {{"time", "s"}, {"x", "m"}});
  SeriesTable surface("surface_height", {{"time", "s"}, {"x", "m"}, {"height", "m"}});
  for (int k = 0; k < 3; ++k) {
    const double t = k * 1e-5;
    shock.append_row(std::vector{t, 0.05 + 500.0 * t});
    for (int i = 0; i <= 10; ++i)
      surface.append_row(std::vector{t, 0.01 * i, 1e-3 * (0.01 * i) + 1e-4 * k});
  }
  sink.write(shock);
  sink.write(surface);
  GasCellArrays g;
  for (int i = 0; i <= 4; ++i) g.x_nodes.push_back(i * 0.01);
  g.y_nodes = {0.0, 0.01};
  g.resize(g.nx(), g.ny());
  for (std::size_t k = 0; k < g.cells(); ++k) {
    g.values("density")[k] = 1.2 + 0.1 * static_cast<double>(k);
    g.values("pressure")[k] = 1e5 + 1e3 * static_cast<double>(k);
    g.values("alpha_p")[k] = 0.1 * static_cast<double>(k);
  }
  VtkSeriesFiles files(dir.string(), "gas", "vtr");
  write_gas_vtr(g, files.next_path(2e-5));
  files.commit(2e-5);
  const auto [status, output] = run(script("summarize_run.py") + " " + dir.string() +
                                    " --times 1e-5 --median-range 0.02 0.06 --station 0.05");
  ASSERT_EQ(status, 0) << output;
  EXPECT_NE(output.find("shock x at t = 0.01 ms: 55.0 mm"), std::string::npos) << output;
  // max at x = 100 mm: 0.1 mm + 0.1 mm; median over 20-60 mm at x = 40 mm: 0.04 + 0.1 mm;
  // at 50 mm: 0.05 + 0.1 mm.
  EXPECT_NE(
      output.find(
          "t = 0.01 ms: surface height max 0.20 mm (at x = 100 mm); median over 20-60 mm 0.14 mm; "
          "at x=50 mm 0.15 mm"),
      std::string::npos)
      << output;
  EXPECT_NE(
      output.find("last gas file gas_000000.vtr: cells 4, finite True, rho min 1.200, p min 1e+05, "
                  "alpha_p max 0.300 (alpha_g min 0.700)"),
      std::string::npos)
      << output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dustlift

namespace dustlift {
namespace {

/// analysis/accuracy_cost.py --tiny: the report's machinery on a two-by-two study.
/// Sod with first order and MUSCL-3 at 50 and 100 cells, and the suite's mini coupled scene at
/// DEM Courant 0.1 / 0.2 and with Magnus on / off: a CSV row per setting with a finite error and
/// wall time, the errors ordered as they must be, the report and its plots written.
TEST_F(AnalysisScripts, AccuracyCostReportsEverySettingWithAFiniteErrorAndWallTime) {
  const auto dir = fresh_dir("accuracy_cost");
  {
    std::ifstream in(std::string(DUSTLIFT_SOURCE_DIR) + "/tests/support/shock_over_dust.hpp");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto a = text.find("R\"(") + 3, b = text.find(")\";", a);
    std::ofstream(dir / "mini.toml") << text.substr(a, b - a);
  }
  const std::string build = fs::path(DUSTLIFT_BINARY).parent_path().string();
  const auto [status, output] =
      run(script("accuracy_cost.py") + " --tiny --build " + build + " --coupled-scene " +
          (dir / "mini.toml").string() + " --work " + (dir / "work").string() + " --report " +
          (dir / "report" / "accuracy-cost.md").string());
  ASSERT_EQ(status, 0) << output;
  std::ifstream csv(dir / "report" / "accuracy-cost" / "accuracy_cost.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("study,setting,reference,error,error_unit,wall_s,steps", 0), 0u) << line;
  std::map<std::string, double> error;
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',') && f.size() < 7;) f.push_back(cell);
    ASSERT_EQ(f.size(), 7u) << line;
    const double e = std::stod(f[3]), wall = std::stod(f[5]);
    EXPECT_TRUE(std::isfinite(e) && e >= 0.0) << line;
    EXPECT_TRUE(std::isfinite(wall) && wall > 0.0) << line;
    EXPECT_GT(std::stoi(f[6]), 0) << line;
    error[f[0] + "/" + f[1]] = e;
    ++rows;
  }
  EXPECT_EQ(rows, 8) << "4 gas + 4 coupled settings";
  ASSERT_EQ(error.size(), 8u);
  // Against the exact solution: MUSCL-3 beats first order, more cells beat fewer.
  EXPECT_LT(error["gas_sod/M3-mm 100 cells CFL 0.6"], error["gas_sod/M3-mm 50 cells CFL 0.6"]);
  EXPECT_LT(error["gas_sod/M3-mm 100 cells CFL 0.6"], error["gas_sod/1st 100 cells CFL 0.6"]);
  EXPECT_GT(error["gas_sod/1st 50 cells CFL 0.6"], 0.01);
  // Each coupled study's reference is zero from itself, the other setting differs.
  EXPECT_EQ(error["courant/nu 0.1"], 0.0);
  EXPECT_EQ(error["effects/all on"], 0.0);
  EXPECT_GT(error["effects/no Magnus"], 0.0);
  for (const char* png : {"gas_sod.png", "coupled.png"})
    EXPECT_GT(fs::file_size(dir / "report" / "accuracy-cost" / png), 10'000u) << png;
  std::ifstream md(dir / "report" / "accuracy-cost.md");
  const std::string report((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("## How to choose"), std::string::npos) << report;
  fs::remove_all(dir);
}

/// A sweep folder as `dustlift sweep` writes it, for the plotting scripts: summary.csv with
/// the varied keys' columns, and per run its resolved scene and dust-cloud series (lifted
/// mass `lifted` kg/m at the end, share `share`).
void write_cloud_sweep(const fs::path& dir, const std::vector<std::string>& columns,
                       const std::vector<std::pair<std::string, std::vector<std::string>>>& runs,
                       const std::vector<std::string>& resolved, const std::vector<double>& lifted,
                       const std::vector<double>& share) {
  fs::create_directories(dir);
  std::ofstream summary(dir / "summary.csv");
  summary << "run";
  for (const auto& c : columns) summary << "," << c;
  summary << ",run_index_1,exit_status_1\n";
  for (std::size_t r = 0; r < runs.size(); ++r) {
    summary << "\"" << runs[r].first << "\"";  // quoted: a sweep's folder names hold commas
    for (const auto& v : runs[r].second) summary << "," << v;
    summary << "," << r << ",0\n";
    const fs::path run = dir / runs[r].first;
    fs::create_directories(run / "series");
    std::ofstream(run / "scene.resolved.toml") << resolved[r];
    std::ofstream cloud(run / "series" / "dust_cloud.csv");
    cloud << "time_s,lifted_mass_kg_per_m,lifted_share_1,height_p50_m,height_p90_m,height_p99_m,"
             "cloud_top_m,"
             "explosible_area_m2,lifted_temperature_max_K,lifted_temperature_mean_K,first_lifted_"
             "behind_shock_m,"
             "densest_lifted_behind_shock_m,explosible_mass_kg_per_m,filter_width_m,"
             "entrainment_rate_kg_per_m_s\n";
    for (int k = 0; k <= 4; ++k) {
      const double f = k / 4.0;
      cloud << 0.05e-3 * k << "," << lifted[r] * f << "," << share[r] * f
            << ",1e-4,1e-3,2e-3,3e-3,5e-5,330,305,0.02,0.09," << 0.1 * lifted[r] * f
            << ",0.02,40\n";
    }
  }
}

TEST_F(AnalysisScripts, PlotCloudStudyComparesMassesUnderTheVariedKeysLastWords) {
  // Layers of 0.5 and 1 mm: the thinner lifts a larger share but less mass. The plot and the
  // table give the lifted mass in g per metre of span; each run is named by its varied keys'
  // last words with the values in units ("thickness = 0.5 mm, mach = 1.5").
  const auto dir = fresh_dir("cloud_study");
  write_cloud_sweep(dir, {"particles_layer_thickness", "initial_mach"},
                    {{"particles.layer.thickness=0.0005,initial.mach=1.5", {"0.0005", "1.5"}},
                     {"particles.layer.thickness=0.001,initial.mach=1.5", {"0.001", "1.5"}}},
                    {"[initial]\nmach = 1.5\n[particles.layer]\nthickness = 0.0005\n",
                     "[initial]\nmach = 1.5\n[particles.layer]\nthickness = 0.001\n"},
                    {4.0e-3, 6.0e-3}, {0.09, 0.07});
  const auto [status, output] = run(script("plot_cloud_study.py") + " " + dir.string() +
                                    " --table " + (dir / "table.md").string());
  ASSERT_EQ(status, 0) << output;
  EXPECT_NE(output.find("| thickness = 0.5 mm, mach = 1.5 | 0.200 | 4 | 9 |"), std::string::npos)
      << output;
  EXPECT_NE(output.find("| thickness = 1 mm, mach = 1.5 | 0.200 | 6 | 7 |"), std::string::npos)
      << output;
  EXPECT_GT(fs::file_size(dir / "dust_cloud.png"), 20'000u);
  EXPECT_TRUE(fs::exists(dir / "table.md"));

  // The study: two keys changed together, each its own label item with its unit.
  const auto both = dir / "both";
  write_cloud_sweep(both, {"particles_layer_y_min", "grid_y_start"},
                    {{"a", {"-0.00025", "-0.00025"}}, {"b", {"-0.0005", "-0.0005"}}},
                    {"[grid.y]\nstart = -0.00025\n[particles.layer]\ny_min = -0.00025\n",
                     "[grid.y]\nstart = -0.0005\n[particles.layer]\ny_min = -0.0005\n"},
                    {1e-3, 2e-3}, {0.1, 0.1});
  const auto [status2, output2] = run(script("plot_cloud_study.py") + " " + both.string());
  ASSERT_EQ(status2, 0) << output2;
  EXPECT_NE(output2.find("| y_min = -0.25 mm, start = -0.25 mm |"), std::string::npos) << output2;
  EXPECT_EQ(output2.find("min = -0.00025"), std::string::npos) << output2;
  // plot_sweep.py names its curves the same way (its runs have no surface series here).
  const auto [status3, output3] =
      run(std::string(kPython) + " -c 'import sys; sys.path.insert(0, \"" + DUSTLIFT_SOURCE_DIR +
          "/analysis\"); from sweep_labels import short_names, value_text; "
          "print(short_names([\"grid.x.start\", \"grid.y.start\", \"initial.mach\"]), "
          "value_text(\"40e-6\", \"m\"), value_text(\"101325\", \"Pa\"), value_text(\"0.2e-3\", "
          "\"s\"))'");
  ASSERT_EQ(status3, 0) << output3;
  EXPECT_NE(
      output3.find("'grid.x.start': 'x.start', 'grid.y.start': 'y.start', 'initial.mach': 'mach'"),
      std::string::npos)
      << output3;
  EXPECT_NE(output3.find("40 µm 101.325 kPa 0.2 ms"), std::string::npos) << output3;
  fs::remove_all(dir);
}

TEST_F(AnalysisScripts, CloudConvergenceComparesRunsThatDifferInOneSetting) {
  // Parcel ratios 2 and 4 on 0.25 and 0.5 mm cells: lifted 4.0, 4.4, 5.0 and 5.5 g/m. The
  // differences are taken only between runs that differ in the ratio alone or the cell alone:
  // ratio 2 -> 4 is +25 % on either grid, 0.5 -> 0.25 mm cells -9.1 % at either ratio; the
  // explosible mass (a tenth of the lifted here) moves alike; the entrainment over the second
  // half is half the lifted mass over 0.1 ms.
  const auto dir = fresh_dir("cloud_convergence");
  const auto scene = [](const char* ratio, const char* cell) {
    return std::string("[particles]\nparcel_ratio = ") + ratio +
           "\n[particles.layer]\ny_max = 0.0\n[grid.x]\ncell_size = " + cell +
           "\n#   output.cloud_lift_height = 1.5e-05   # from particles.diameter\n";
  };
  write_cloud_sweep(dir, {"particles_parcel_ratio", "grid_x_cell_size"},
                    {{"r2c25", {"2", "0.00025"}},
                     {"r2c50", {"2", "0.0005"}},
                     {"r4c25", {"4", "0.00025"}},
                     {"r4c50", {"4", "0.0005"}}},
                    {scene("2.0", "0.00025"), scene("2.0", "0.0005"), scene("4.0", "0.00025"),
                     scene("4.0", "0.0005")},
                    {4.0e-3, 4.4e-3, 5.0e-3, 5.5e-3}, {0.1, 0.1, 0.1, 0.1});
  // Each run's final parcels: class 0 (D = 0.1 mm) has 3 parcels in its top row and 3 below,
  // 2 of the top row and 2 below above the lift height (15 um; one top parcel at 10 um is not):
  // 4/3 of a top row lifted; class 1 (D = 0.2 mm) 1 of its 2 top parcels: 0.5.
  for (const char* name : {"r2c25", "r2c50", "r4c25", "r4c50"}) {
    const auto [h5, h5_output] =
        run(std::string(kPython) + " -c 'import h5py; f = h5py.File(\"" +
            (dir / name / "checkpoint.h5").string() +
            "\", \"w\"); d = {\"y_initial\": [-5e-5] * 3 + [-1.5e-4] * 3 + [-1e-4] * 2, "
            "\"y\": [1e-3, 1e-3, 1e-5, 1e-3, 1e-3, -1.5e-4, 1e-3, -1e-4], "
            "\"size_class\": [0.0] * 6 + [1.0] * 2, \"diameter\": [1e-4] * 6 + [2e-4] * 2}; "
            "[f.create_dataset(\"parcels/\" + k, data=v) for k, v in d.items()]'");
    ASSERT_EQ(h5, 0) << h5_output;
  }
  const auto [status, output] = run(script("cloud_convergence.py") + " " + dir.string());
  ASSERT_EQ(status, 0) << output;
  EXPECT_NE(output.find("| ratio 4, 0.25 mm cells | 1.33 | 0.50 |"), std::string::npos) << output;
  // lifted, above 1 mm (not in these series), explosible, entrainment, its 2nd-half mean.
  EXPECT_NE(output.find("| ratio 2, 0.25 mm cells | 0.200 | 4 | nan | 0.4 | 40 | 20 |"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("| ratio 2, 0.5 mm cells -> ratio 2, 0.25 mm cells | -9.1 | n/a | -9.1 | "
                        "+0.0 | -9.1 |"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("| ratio 2, 0.5 mm cells -> ratio 4, 0.5 mm cells | +25.0 | n/a | +25.0 |"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("| ratio 2, 0.25 mm cells -> ratio 4, 0.25 mm cells | +25.0 |"),
            std::string::npos)
      << output;
  // Two settings changed at once are no pair.
  EXPECT_EQ(output.find("ratio 2, 0.5 mm cells -> ratio 4, 0.25 mm cells"), std::string::npos)
      << output;
  EXPECT_GT(fs::file_size(dir / "convergence.png"), 10'000u);
  fs::remove_all(dir);
}

TEST_F(AnalysisScripts, ClosureSensitivityTabulatesTwoRunsAndTheirDifference) {
  // Two runs of one scene: 4 and 6 g/m lifted (+50 %), the station at 30 mm 0.5 and 0.25 mm
  // (-50 %), the first lifted dust 50 and 75 mm behind the shock (+50 %). The row of a time
  // past --time is not read.
  const auto dir = fresh_dir("closure_sensitivity");
  const auto write_run = [&](const std::string& name, double lifted, double h30, double behind) {
    const auto series = dir / name / "series";
    fs::create_directories(series);
    std::ofstream(series / "dust_cloud.csv")
        << "time_s,lifted_mass_kg_per_m,lifted_share_1,shock_x_m,first_lifted_behind_shock_m\n"
        << "0,0,0,0,nan\n"
        << "0.0003," << lifted << "," << lifted / 0.1 << ",0.144," << behind << "\n"
        << "0.0004,1,10,0.2,0.01\n";
    std::ofstream(series / "surface_height_stations.csv")
        << "time_s,height_at_x0p03_m\n0,0\n0.0003," << h30 << "\n0.0004,1\n";
  };
  write_run("a", 4e-3, 0.5e-3, 0.050);
  write_run("b", 6e-3, 0.25e-3, 0.075);
  const auto [status, output] =
      run(script("closure_sensitivity.py") + " first=" + (dir / "a").string() +
          " second=" + (dir / "b").string() + " --time 3e-4");
  ASSERT_EQ(status, 0) << output;
  EXPECT_NE(output.find("At t = 0.3 ms (shock at x = 144 mm)"), std::string::npos) << output;
  EXPECT_NE(output.find("| lifted mass (g/m) | 4 | 6 | +50 % |"), std::string::npos) << output;
  EXPECT_NE(output.find("| surface at the station x = 30 mm (mm) | 0.5 | 0.25 | -50 % |"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("| first lifted dust behind the shock (mm) | 50 | 75 | +50 % |"),
            std::string::npos)
      << output;
  // A folder that is not a run is named.
  const auto [bad, message] =
      run(script("closure_sensitivity.py") + " x=" + (dir / "missing").string());
  EXPECT_NE(bad, 0);
  EXPECT_NE(message.find("no series/dust_cloud.csv"), std::string::npos) << message;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dustlift
