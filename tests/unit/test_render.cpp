// Offscreen rendering end to end: synthetic gas + parcel series written by the writers,
// rendered by pvstates/render.py under a private Xvfb (scripts/with-xvfb.sh); the PNGs must exist,
// have a plausible size and not be a uniform image (pvbatch exits 0 even when loading failed).
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>

#include "insitu/gas_cells.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/core/derivatives.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

namespace fs = std::filesystem;

bool on_path(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

/// Two outputs of a shock running over a dust layer: pressure step at x_s(t), shear
/// flow behind it, a sine-topped layer of parcels.
void write_synthetic_run(const fs::path& dir) {
  GasCellArrays g;
  for (int i = 0; i <= 120; ++i) g.x_nodes.push_back(-0.02 + 0.1 * i / 120.0);
  double y = 0.0, w = 2.5e-4;
  g.y_nodes.push_back(y);
  for (int j = 0; j < 60; ++j) g.y_nodes.push_back(y += (j < 40 ? w : (w *= 1.08)));
  g.resize(g.nx(), g.ny());
  const auto xc = g.x_centers(), yc = g.y_centers();
  VtkSeriesFiles gas_files(dir.string(), "gas", "vtr");
  ParcelSeriesWriter parcel_writer(dir.string());
  for (int output = 0; output < 2; ++output) {
    const double t = output * 5e-5, xs = 0.01 + 500.0 * t;
    for (std::size_t j = 0; j < g.ny(); ++j)
      for (std::size_t i = 0; i < g.nx(); ++i) {
        const std::size_t k = i + g.nx() * j;
        const bool behind = xc[i] < xs;
        g.values("pressure")[k] = behind ? 2.2e5 - 2e5 * std::exp(-yc[j] / 3e-3) * 0.2 : 1.01325e5;
        g.values("density")[k] = behind ? 2.0 : 1.2;
        g.values("velocity", 0)[k] = behind ? 250.0 * (1.0 - std::exp(-yc[j] / 1e-3)) : 0.0;
        g.values("velocity", 1)[k] = behind ? 5.0 * std::sin(200.0 * xc[i]) : 0.0;
        g.values("temperature")[k] = behind ? 380.0 : 300.0;
        g.values("mach")[k] = g.values("velocity", 0)[k] / 340.0;
        g.values("alpha_p")[k] = yc[j] < 2e-3 ? 0.59 : 0.0;
        // A dust cloud over the layer behind the shock, thinning upwards over decades.
        g.values("dust_concentration")[k] = yc[j] < 2e-3 ? 578.0
                                            : behind ? 578.0 * std::exp(-(yc[j] - 2e-3) / 0.4e-3)
                                                     : 0.0;
      }
    {
      const Grid2D grid(Axis(g.x_nodes, 2), Axis(g.y_nodes, 2));
      Field2D u(grid), v(grid);
      for (std::size_t j = 0; j < g.ny(); ++j)
        for (std::size_t i = 0; i < g.nx(); ++i) {
          u(static_cast<int>(i), static_cast<int>(j)) = g.values("velocity", 0)[i + g.nx() * j];
          v(static_cast<int>(i), static_cast<int>(j)) = g.values("velocity", 1)[i + g.nx() * j];
        }
      g.values("vorticity") = vorticity_z(grid, u, v);
    }
    write_gas_vtr(g, gas_files.next_path(t));
    gas_files.commit(t);

    const std::size_t n = 3000;
    std::vector<double> px(n), py(n), vx(n, 1.0), vy(n, 0.0), d(n, 1e-4);
    for (std::size_t k = 0; k < n; ++k) {
      px[k] = 0.07 * static_cast<double>(k % 300) / 300.0;
      const double top = 2e-3 + (px[k] < xs ? 1.5e-3 * std::sin(300.0 * px[k]) * output : 0.0);
      py[k] = top * static_cast<double>(k / 300 + 0.5) / 10.0;
    }
    ParcelArraysView view;
    view.count = n;
    view.position = {px, py};
    view.add("velocity", Vec2Columns{vx, vy});
    view.add("diameter", d);
    parcel_writer.write(view, t);
  }
}

/// Pixels whose RGB differ between two images of the same size, in rows [row0, row1) counted
/// from the top (all rows when row1 = 0); -1 when the sizes differ.
long differing_pixels(const fs::path& a, const fs::path& b, int row0 = 0, int row1 = 0) {
  vtkNew<vtkPNGReader> ra, rb;
  ra->SetFileName(a.string().c_str());
  rb->SetFileName(b.string().c_str());
  ra->Update();
  rb->Update();
  int da[3], db[3];
  ra->GetOutput()->GetDimensions(da);
  rb->GetOutput()->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1]) return -1;
  auto* pa = vtkUnsignedCharArray::SafeDownCast(ra->GetOutput()->GetPointData()->GetScalars());
  auto* pb = vtkUnsignedCharArray::SafeDownCast(rb->GetOutput()->GetPointData()->GetScalars());
  const int nc = pa->GetNumberOfComponents();
  if (row1 <= 0) row1 = da[1];
  long n = 0;
  for (int top = row0; top < row1; ++top) {
    const int row = da[1] - 1 - top;  // VTK images start at the bottom row
    for (int x = 0; x < da[0]; ++x) {
      const vtkIdType p = static_cast<vtkIdType>(row) * da[0] + x;
      bool same = true;
      for (int ch = 0; ch < std::min(nc, 3); ++ch)
        same = same && pa->GetValue(p * nc + ch) == pb->GetValue(p * nc + ch);
      n += !same;
    }
  }
  return n;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct ImageCheck {
  int width = 0, height = 0;
  std::size_t distinct_colors = 0;
  int channel_spread = 0;  // max over RGB of (max - min)
};

ImageCheck inspect_png(const fs::path& path) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  ImageCheck c;
  int dims[3];
  image->GetDimensions(dims);
  c.width = dims[0];
  c.height = dims[1];
  auto* pixels = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (!pixels) return c;
  const int nc = pixels->GetNumberOfComponents();
  std::set<long> colors;
  int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
  for (vtkIdType p = 0; p < pixels->GetNumberOfTuples(); ++p) {
    long key = 0;
    for (int ch = 0; ch < std::min(nc, 3); ++ch) {
      const int v = pixels->GetValue(p * nc + ch);
      lo[ch] = std::min(lo[ch], v);
      hi[ch] = std::max(hi[ch], v);
      key = key * 256 + v;
    }
    colors.insert(key);
  }
  c.distinct_colors = colors.size();
  for (int ch = 0; ch < 3; ++ch) c.channel_spread = std::max(c.channel_spread, hi[ch] - lo[ch]);
  return c;
}

void expect_rendered(const fs::path& png) {
  ASSERT_TRUE(fs::exists(png)) << png << " was not written";
  EXPECT_GT(fs::file_size(png), 10000u) << png;
  const ImageCheck c = inspect_png(png);
  EXPECT_GE(c.width, 800) << png;
  EXPECT_GE(c.height, 300) << png;
  // A colour map over a field plus text: many colours; a blank render has one or two.
  EXPECT_GT(c.distinct_colors, 50u) << png;
  EXPECT_GT(c.channel_spread, 150) << png;
}

class Render : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!on_path("Xvfb") || !on_path("pvbatch"))
      FAIL() << "Xvfb and pvbatch are needed for offscreen rendering; install them with "
                "scripts/install-deps.sh (packages xvfb, xauth, paraview, python3-paraview)";
    // Each test its own folder: the shipped state must find data away from where it was saved.
    dir_ = testing::scratch_dir(
        std::string("render_") + ::testing::UnitTest::GetInstance()->current_test_info()->name(),
        false);
    write_synthetic_run(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);  // keep the PNGs and render.log of a failure
  }
  /// Runs render.py with extra arguments under a private X server (scripts/with-xvfb.sh:
  /// Xvfb picks its own free display, so concurrent renders never race for one); returns
  /// wall seconds.
  double render(const std::string& extra) {
    const std::string script = std::string(DUSTLIFT_SOURCE_DIR) + "/pvstates/render.py";
    const fs::path log = dir_ / "render.log";
    const auto start = std::chrono::steady_clock::now();
    const std::string command = "bash " + std::string(DUSTLIFT_SOURCE_DIR) +
                                "/scripts/with-xvfb.sh pvbatch " + script + " " + dir_.string() +
                                " " + extra + " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(status, 0) << command << "\n" << read_log(log);
    return seconds;
  }
  static std::string read_log(const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  fs::path dir_;
};

TEST_F(Render, PressureWithParcelsAndVorticityPngsAreNotBlank) {
  const double seconds = render("--save-state " + (dir_ / "saved.pvsm").string());
  RecordProperty("render_seconds", std::to_string(seconds));
  std::cout << "render.py (2 PNGs + state): " << seconds << " s\n";
  expect_rendered(dir_ / "figures" / "pressure_000001.png");
  expect_rendered(dir_ / "figures" / "vorticity_000001.png");
  EXPECT_FALSE(fs::exists(dir_ / "figures" / "pressure_000000.png"));  // last time only
  EXPECT_TRUE(fs::exists(dir_ / "saved.pvsm"));
  // A user sees no VTK error lines (deleting the first view before making the second printed
  // four about shader vertex attributes under Mesa llvmpipe).
  const std::string log = read_log(dir_ / "render.log");
  EXPECT_EQ(log.find("ERR|"), std::string::npos) << log;
  // The state a run folder gets names its data without the folder, so it opens anywhere.
  const std::string state = read_text(dir_ / "pressure_parcels.pvsm");
  EXPECT_NE(state.find("value=\"gas.pvd\""), std::string::npos);
  EXPECT_EQ(state.find(dir_.string()), std::string::npos)
      << "no absolute path of this run in the state";
}

TEST_F(Render, ShippedStateHasRelativePathsALiveTimeLabelAndADataDrivenRange) {
  const std::string state = std::string(DUSTLIFT_SOURCE_DIR) + "/pvstates/pressure_parcels.pvsm";
  const std::string xml = read_text(state);
  EXPECT_NE(xml.find("<Element index=\"0\" value=\"gas.pvd\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<Element index=\"0\" value=\"parcels.pvd\"/>"), std::string::npos);
  EXPECT_FALSE(std::regex_search(xml, std::regex("value=\"/[A-Za-z]"))) << "no absolute path";
  EXPECT_NE(xml.find("type=\"PythonAnnotation\""), std::string::npos)
      << "a label that follows the time";
  EXPECT_EQ(xml.find("t = 0.0500 ms"), std::string::npos) << "no fixed time text";
  // AutomaticRescaleRangeMode 3: "Clamp and update every timestep".
  EXPECT_NE(xml.find("AutomaticRescaleRangeMode\" number_of_elements=\"1\">\n        <Element "
                     "index=\"0\" value=\"3\"/>"),
            std::string::npos);
  // Rendered with another run's data at each of its times: the images change with time,
  // the label too (its rows at the top of the image).
  render("--state " + state + " --all");
  // Saved from a run that ended at 2e-5 s, its animation runs to this run's last time.
  EXPECT_NE(read_log(dir_ / "render.log")
                .find("state: 2 times from 0 to 5e-05 s; animation from 0 to 5e-05 s"),
            std::string::npos)
      << read_log(dir_ / "render.log");
  const fs::path first = dir_ / "figures" / "state_000000.png",
                 last = dir_ / "figures" / "state_000001.png";
  expect_rendered(first);
  expect_rendered(last);
  const long changed = differing_pixels(first, last), label = differing_pixels(first, last, 0, 30);
  std::cout << "shipped state: " << changed << " pixels differ between t = 0 and t = 5e-5 s, "
            << label << " of them in the label rows\n";
  EXPECT_GT(changed, 20000);
  EXPECT_GT(label, 20);
}

TEST_F(Render, AChosenFieldZoomedStretchedOnALogScaleHasTheRequestedSize) {
  // The dust concentration on a log scale in a box over the layer's upstream part, y drawn
  // twice as long, the parcels on top, at a requested size.
  render(
      "--field dust_concentration --log --x 0.0 0.03 --y 0.0 0.006 --stretch 2 --parcels --size "
      "1000 500");
  const fs::path png = dir_ / "figures" / "dust_concentration_000001.png";
  expect_rendered(png);
  const ImageCheck c = inspect_png(png);
  EXPECT_EQ(c.width, 1000);
  EXPECT_EQ(c.height, 500);
  // The view's state: data named relative to the run, the zoom box, the log scale.
  const std::string state = read_text(dir_ / "dust_concentration.pvsm");
  EXPECT_NE(state.find("value=\"gas.pvd\""), std::string::npos);
  EXPECT_EQ(state.find(dir_.string()), std::string::npos)
      << "no absolute path of this run in the state";
  EXPECT_NE(state.find("name=\"UseLogScale\""), std::string::npos);
  EXPECT_NE(state.find("type=\"Clip\""), std::string::npos) << "the zoom box";
  // The same field over the whole channel at another time: another image.
  render("--field dust_concentration --log --size 1000 500 --time 0 --figures " +
         (dir_ / "whole").string());
  const fs::path whole = dir_ / "whole" / "dust_concentration_000000.png";
  expect_rendered(whole);
  EXPECT_GT(differing_pixels(png, whole), 50000) << "the zoom and the time change the picture";
  // Options that need --field, and a box the wrong way round, are refused.
  const std::string script = std::string(DUSTLIFT_SOURCE_DIR) + "/pvstates/render.py";
  for (const char* bad : {"--log", "--x 0.03 0.0 --field mach", "--field nonsense"}) {
    const std::string command = "bash " + std::string(DUSTLIFT_SOURCE_DIR) +
                                "/scripts/with-xvfb.sh pvbatch " + script + " " + dir_.string() +
                                " " + bad + " > /dev/null 2>&1";
    EXPECT_NE(std::system(command.c_str()), 0) << bad;
  }
}

TEST_F(Render, RunSceneScriptTakesPathsRelativeToTheCallersFolder) {
  // scene and output folder given relative to where the user stands, not to the repository.
  const fs::path cwd = dir_ / "user";
  fs::create_directories(cwd);
  fs::copy_file(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/verification/sod.toml",
                cwd / "tube.toml");
  const std::string command =
      "cd " + cwd.string() + " && bash " + std::string(DUSTLIFT_SOURCE_DIR) +
      "/scripts/run-scene.sh tube.toml out --set grid.x.cells=100 --threads 1 > script.log 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << read_text(cwd / "script.log");
  EXPECT_TRUE(fs::exists(cwd / "out" / "gas.pvd"));
  EXPECT_TRUE(fs::exists(cwd / "out" / "figures" / "shock_position.png"));
  expect_rendered(cwd / "out" / "figures" / "pressure_000004.png");
  EXPECT_TRUE(fs::exists(cwd / "out" / "pressure_parcels.pvsm"));
  // Options after -- go to render.py: a chosen field in a zoom box.
  const std::string field = "cd " + cwd.string() + " && bash " + std::string(DUSTLIFT_SOURCE_DIR) +
                            "/scripts/run-scene.sh tube.toml out2 --set grid.x.cells=100 --threads "
                            "1 -- --field density --x 0.3 0.8 "
                            "--size 900 400 > script2.log 2>&1";
  EXPECT_EQ(std::system(field.c_str()), 0) << read_text(cwd / "script2.log");
  expect_rendered(cwd / "out2" / "figures" / "density_000004.png");
  EXPECT_EQ(inspect_png(cwd / "out2" / "figures" / "density_000004.png").width, 900);
  EXPECT_FALSE(fs::exists(cwd / "out2" / "figures" / "pressure_000004.png"))
      << "the options replace the default views";
}

}  // namespace
}  // namespace dustlift
