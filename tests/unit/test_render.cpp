// Offscreen rendering end to end: synthetic gas + parcel series written by the writers,
// rendered by pvstates/render.py under `xvfb-run -a pvbatch`; the PNGs must exist, have a
// plausible size and not be a uniform image (pvbatch exits 0 even when loading failed).
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
#include <set>
#include <string>

#include "insitu/gas_cells.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/core/derivatives.hpp"

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
        g.pressure[k] = behind ? 2.2e5 - 2e5 * std::exp(-yc[j] / 3e-3) * 0.2 : 1.01325e5;
        g.density[k] = behind ? 2.0 : 1.2;
        g.velocity_x[k] = behind ? 250.0 * (1.0 - std::exp(-yc[j] / 1e-3)) : 0.0;
        g.velocity_y[k] = behind ? 5.0 * std::sin(200.0 * xc[i]) : 0.0;
        g.temperature[k] = behind ? 380.0 : 300.0;
        g.mach[k] = g.velocity_x[k] / 340.0;
        g.alpha_p[k] = yc[j] < 2e-3 ? 0.59 : 0.0;
      }
    vorticity_z(xc, yc, g.velocity_x, g.velocity_y, g.vorticity);
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
    view.velocity = {vx, vy};
    view.diameter = d;
    parcel_writer.write(view, t);
  }
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
    if (!on_path("xvfb-run") || !on_path("pvbatch"))
      FAIL() << "xvfb-run and pvbatch are needed for offscreen rendering; install them with "
                "scripts/install-deps.sh (packages xvfb, xauth, paraview, python3-paraview)";
    // Each test its own folder: the shipped state must find data away from where it was saved.
    dir_ = fs::temp_directory_path() /
           (std::string("dustlift_render_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    write_synthetic_run(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);  // keep the PNGs and render.log of a failure
  }
  /// Runs render.py with extra arguments; returns wall seconds. `xvfb-run -a` picks a free
  /// display by probing lock files, which races when two renders start at once (ctest -j2,
  /// several users): start the probe at a per-process display number and retry once if
  /// the X server connection failed.
  double render(const std::string& extra) {
    const std::string script = std::string(DUSTLIFT_SOURCE_DIR) + "/pvstates/render.py";
    const fs::path log = dir_ / "render.log";
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    std::string command;
    for (int attempt = 0; attempt < 3; ++attempt) {
      const int display = 100 + static_cast<int>((::getpid() * 7 + attempt * 131) % 800);
      command = "xvfb-run -a -n " + std::to_string(display) + " pvbatch " + script + " " +
                dir_.string() + " " + extra + " > " + log.string() + " 2>&1";
      status = std::system(command.c_str());
      if (read_log(log).find("bad X server connection") == std::string::npos) break;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(status, 0) << command << "\nsee " << log;
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
}

TEST_F(Render, ShippedStateRendersTheRunsData) {
  const std::string state = std::string(DUSTLIFT_SOURCE_DIR) + "/pvstates/pressure_parcels.pvsm";
  ASSERT_TRUE(fs::exists(state));
  render("--state " + state);
  expect_rendered(dir_ / "figures" / "state_000001.png");
}

}  // namespace
}  // namespace dustlift
