// ParaView Catalyst in situ, end to end (docs/catalyst.md): a short coupled run
// with the shipped extract and render scripts; the extracts must hold the same arrays as the
// solver's own .vtr/.vtp of the same step, the PNGs must show something and change; a script
// that fails must not stop the run nor touch its other outputs; bad [insitu.catalyst] input
// is exit 2 before anything is written.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLRectilinearGridReader.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>

#include "support/run_cli.hpp"
#include "support/shock_over_dust.hpp"

namespace dustlift {
namespace {

namespace fs = std::filesystem;
using testing::expect_bad_input;
using testing::fresh_dir;
using testing::run_cli;
using testing::write_file;

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

/// The mini coupled scene (93 steps) with an [insitu.catalyst] section.
std::string scene_with_catalyst(const std::string& catalyst_section) {
  return std::string(testing::kShockOverDust) + "\n[insitu.catalyst]\n" + catalyst_section;
}

std::string script(const std::string& name) {
  return std::string(DUSTLIFT_SOURCE_DIR) + "/catalyst/" + name;
}

/// The files listed by a .pvd, in order.
std::vector<fs::path> pvd_files(const fs::path& pvd) {
  const std::string text = read_text(pvd);
  std::vector<fs::path> files;
  const std::regex entry(R"re(file="([^"]+)")re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry);
       it != std::sregex_iterator(); ++it)
    files.push_back(pvd.parent_path() / (*it)[1].str());
  return files;
}

/// The one piece a serial extract (.pvtr/.pvtp) points to.
fs::path only_piece(const fs::path& parallel_file) {
  const std::string text = read_text(parallel_file);
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, std::regex(R"re(<Piece[^>]*Source="([^"]+)")re")))
      << parallel_file;
  return parallel_file.parent_path() / m[1].str();
}

/// Every array of `expected` is in `actual` with the same name, size and values (bitwise).
void expect_same_arrays(vtkFieldData* expected, vtkFieldData* actual, const std::string& what) {
  ASSERT_GT(expected->GetNumberOfArrays(), 0) << what;
  for (int a = 0; a < expected->GetNumberOfArrays(); ++a) {
    vtkDataArray* e = vtkDataArray::SafeDownCast(expected->GetAbstractArray(a));
    if (e == nullptr) continue;
    const std::string name = e->GetName();
    vtkDataArray* g = vtkDataArray::SafeDownCast(actual->GetAbstractArray(name.c_str()));
    ASSERT_NE(g, nullptr) << what << ": no array " << name;
    ASSERT_EQ(g->GetNumberOfTuples(), e->GetNumberOfTuples()) << what << " " << name;
    ASSERT_EQ(g->GetNumberOfComponents(), e->GetNumberOfComponents()) << what << " " << name;
    long long differing = 0;
    for (vtkIdType t = 0; t < e->GetNumberOfTuples(); ++t)
      for (int c = 0; c < e->GetNumberOfComponents(); ++c)
        differing += e->GetComponent(t, c) != g->GetComponent(t, c);
    EXPECT_EQ(differing, 0) << what << ": " << name << " differs in " << differing << " values";
  }
}

void expect_same_vtr(const fs::path& a_path, const fs::path& b_path) {
  vtkNew<vtkXMLRectilinearGridReader> a, b;
  a->SetFileName(a_path.c_str());
  a->Update();
  b->SetFileName(b_path.c_str());
  b->Update();
  ASSERT_EQ(a->GetOutput()->GetNumberOfCells(), b->GetOutput()->GetNumberOfCells()) << a_path;
  ASSERT_GT(a->GetOutput()->GetNumberOfCells(), 0) << a_path;
  expect_same_arrays(a->GetOutput()->GetCellData(), b->GetOutput()->GetCellData(), a_path.string());
}

void expect_same_vtp(const fs::path& a_path, const fs::path& b_path) {
  vtkNew<vtkXMLPolyDataReader> a, b;
  a->SetFileName(a_path.c_str());
  a->Update();
  b->SetFileName(b_path.c_str());
  b->Update();
  ASSERT_EQ(a->GetOutput()->GetNumberOfPoints(), b->GetOutput()->GetNumberOfPoints()) << a_path;
  ASSERT_GT(a->GetOutput()->GetNumberOfPoints(), 0) << a_path;
  expect_same_arrays(a->GetOutput()->GetPointData(), b->GetOutput()->GetPointData(),
                     a_path.string());
}

/// The extract's one piece holds the .vtr's cell arrays and nodes.
void expect_gas_extract_matches(const fs::path& extract, const fs::path& vtr) {
  expect_same_vtr(vtr, only_piece(extract));
  vtkNew<vtkXMLRectilinearGridReader> a, b;
  a->SetFileName(vtr.c_str());
  a->Update();
  b->SetFileName(only_piece(extract).c_str());
  b->Update();
  for (int axis = 0; axis < 2; ++axis) {
    vtkDataArray* ea =
        axis == 0 ? a->GetOutput()->GetXCoordinates() : a->GetOutput()->GetYCoordinates();
    vtkDataArray* eb =
        axis == 0 ? b->GetOutput()->GetXCoordinates() : b->GetOutput()->GetYCoordinates();
    ASSERT_EQ(ea->GetNumberOfTuples(), eb->GetNumberOfTuples());
    for (vtkIdType k = 0; k < ea->GetNumberOfTuples(); ++k)
      EXPECT_EQ(ea->GetComponent(k, 0), eb->GetComponent(k, 0));
  }
}

/// The extract's one piece holds the .vtp's points and point arrays, with id.
void expect_parcel_extract_matches(const fs::path& extract, const fs::path& vtp) {
  expect_same_vtp(vtp, only_piece(extract));
  vtkNew<vtkXMLPolyDataReader> a, b;
  a->SetFileName(vtp.c_str());
  a->Update();
  b->SetFileName(only_piece(extract).c_str());
  b->Update();
  for (vtkIdType k = 0; k < a->GetOutput()->GetNumberOfPoints(); ++k) {
    double pa[3], pb[3];
    a->GetOutput()->GetPoint(k, pa);
    b->GetOutput()->GetPoint(k, pb);
    ASSERT_TRUE(pa[0] == pb[0] && pa[1] == pb[1]) << extract << " point " << k;
  }
  EXPECT_NE(b->GetOutput()->GetPointData()->GetArray("id"), nullptr) << extract;
}

/// The RGB triples of a PNG.
std::vector<unsigned char> png_pixels(const fs::path& p, int& width) {
  vtkNew<vtkPNGReader> r;
  r->SetFileName(p.c_str());
  r->Update();
  vtkImageData* img = r->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  width = dims[0];
  auto* a = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetScalars());
  std::vector<unsigned char> rgb;
  if (a == nullptr) return rgb;
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
    for (int c = 0; c < 3; ++c) rgb.push_back(static_cast<unsigned char>(a->GetComponent(t, c)));
  return rgb;
}

#ifdef DUSTLIFT_TEST_HAS_CATALYST

TEST(Catalyst, ExtractsEqualTheSolversFilesAndRendersChange) {
  const fs::path dir = fresh_dir("catalyst_extracts");
  write_file(dir / "scene.toml",
             scene_with_catalyst("scripts = [\"" + script("extracts.py") + "\", \"" +
                                 script("pressure_parcels.py") + "\"]\ninterval_steps = 50\n"));
  const fs::path out = dir / "out";
  const auto r = run_cli("run " + (dir / "scene.toml").string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string log = read_text(out / "run.log");
  EXPECT_NE(log.find("catalyst: pipeline " + script("extracts.py") + " (script version 2)"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("catalyst: 3 deliveries"), std::string::npos) << "steps 0, 50 and the last:\n"
                                                                   << log;
  EXPECT_EQ(log.find("Traceback"), std::string::npos) << log;

  // Step 0 is the first output of the .pvd, the last step (93) its last.
  const auto gas_files = pvd_files(out / "gas.pvd");
  const auto parcel_files = pvd_files(out / "parcels.pvd");
  ASSERT_GE(gas_files.size(), 2u);
  ASSERT_GE(parcel_files.size(), 2u);
  const fs::path c = out / "catalyst";
  ASSERT_TRUE(fs::exists(c / "gas_000000.pvtr")) << r.output;
  ASSERT_TRUE(fs::exists(c / "gas_000050.pvtr"));
  ASSERT_TRUE(fs::exists(c / "gas_000093.pvtr")) << "the last step is always delivered";
  expect_gas_extract_matches(c / "gas_000000.pvtr", gas_files.front());
  expect_gas_extract_matches(c / "gas_000093.pvtr", gas_files.back());
  expect_parcel_extract_matches(c / "parcels_000000.pvtp", parcel_files.front());
  expect_parcel_extract_matches(c / "parcels_000093.pvtp", parcel_files.back());

  // Renders: not blank (many colours, most of the image not background) and changed.
  int w0 = 0, w1 = 0;
  const auto first = png_pixels(c / "pressure_parcels_000000.png", w0);
  const auto last = png_pixels(c / "pressure_parcels_000093.png", w1);
  ASSERT_EQ(w0, 1600);
  ASSERT_EQ(first.size(), last.size());
  ASSERT_FALSE(first.empty());
  std::set<int> colours;
  long long non_white = 0, changed = 0;
  for (std::size_t k = 0; k + 2 < last.size(); k += 3) {
    colours.insert(last[k] << 16 | last[k + 1] << 8 | last[k + 2]);
    non_white += !(last[k] == 255 && last[k + 1] == 255 && last[k + 2] == 255);
    changed += first[k] != last[k] || first[k + 1] != last[k + 1] || first[k + 2] != last[k + 2];
  }
  const double pixels = static_cast<double>(last.size() / 3);
  EXPECT_GT(colours.size(), 20u) << "a pressure map with a colour bar has many colours";
  EXPECT_GT(non_white / pixels, 0.5) << "the channel fills most of the view";
  EXPECT_GT(changed / pixels, 0.1) << "the shock ran in between: the picture must change";
}

TEST(Catalyst, AFailingScriptLeavesTheRunAndItsOutputsIntact) {
  const fs::path dir = fresh_dir("catalyst_failing");
  write_file(dir / "broken.py", R"(# script-version: 2
from paraview.simple import *
from paraview import catalyst
gas = TrivialProducer(registrationName='gas')
options = catalyst.Options()
def catalyst_execute(info):
    raise RuntimeError('deliberately broken pipeline at step %d' % info.timestep)
)");
  write_file(dir / "with.toml",
             scene_with_catalyst("scripts = [\"broken.py\"]\ninterval_steps = 40\n"));
  write_file(dir / "without.toml", testing::kShockOverDust);
  const auto r =
      run_cli("run " + (dir / "with.toml").string() + " --out " + (dir / "with").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string log = read_text(dir / "with" / "run.log");
  EXPECT_NE(log.find("catalyst: Traceback (most recent call last):"), std::string::npos) << log;
  EXPECT_NE(log.find("RuntimeError: deliberately broken pipeline at step 40"), std::string::npos)
      << log;
  EXPECT_NE(log.find("catalyst: a pipeline failed at step 40"), std::string::npos) << log;
  EXPECT_NE(log.find("done: t = 2.000000e-05 s after 93 steps"), std::string::npos) << log;

  // Everything else is what a run without Catalyst writes, byte for byte.
  const auto r2 =
      run_cli("run " + (dir / "without.toml").string() + " --out " + (dir / "without").string());
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  const auto a = pvd_files(dir / "with" / "gas.pvd"), b = pvd_files(dir / "without" / "gas.pvd");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (std::size_t k = 0; k < a.size(); ++k) expect_same_vtr(a[k], b[k]);
  const auto pa = pvd_files(dir / "with" / "parcels.pvd"),
             pb = pvd_files(dir / "without" / "parcels.pvd");
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t k = 0; k < pa.size(); ++k) expect_same_vtp(pa[k], pb[k]);
  int series = 0;
  for (const auto& e : fs::directory_iterator(dir / "without" / "series")) {
    if (e.path().extension() != ".csv") continue;
    ++series;
    EXPECT_EQ(read_text(dir / "with" / "series" / e.path().filename()), read_text(e.path()))
        << e.path().filename();
  }
  EXPECT_GE(series, 5);
}

TEST(Catalyst, ASimulatedTimeIntervalDeliversOncePerIntervalAndTheEnd) {
  const fs::path dir = fresh_dir("catalyst_interval");
  // 20 us run: t = 0, the first steps at or past 5, 10, 15 us, and the end (20 us) once.
  write_file(dir / "scene.toml", scene_with_catalyst("scripts = [\"" + script("do_nothing.py") +
                                                     "\"]\ninterval = 5e-6\n"));
  const auto r =
      run_cli("run " + (dir / "scene.toml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string log = read_text(dir / "out" / "run.log");
  EXPECT_NE(log.find("catalyst: 5 deliveries"), std::string::npos) << log;
  EXPECT_NE(log.find("catalyst: 5 frames gathered"), std::string::npos) << log;
}

#else

TEST(Catalyst, ABuildWithoutCatalystRefusesTheSectionBeforeWriting) {
  const fs::path dir = fresh_dir("catalyst_absent");
  write_file(dir / "s.py", "# script-version: 2\n");
  write_file(dir / "scene.toml", scene_with_catalyst("scripts = [\"s.py\"]\n"));
  const fs::path out = dir / "out";
  expect_bad_input(run_cli("run " + (dir / "scene.toml").string() + " --out " + out.string()),
                   "built without ParaView Catalyst", out, "no Catalyst");
}

#endif

TEST(Catalyst, BadSectionIsExitTwoNamingTheKey) {
  const fs::path dir = fresh_dir("catalyst_bad");
  write_file(dir / "s.py", "# script-version: 2\n");
  const struct {
    std::string section, named;
  } rows[] = {
      {"scripts = [\"missing.py\"]\n", "insitu.catalyst.scripts"},
      {"scripts = []\n", "insitu.catalyst.scripts"},
      {"scripts = [\"s.py\"]\ninterval = 1e-6\ninterval_steps = 2\n", "insitu.catalyst.interval"},
      {"scripts = [\"s.py\"]\ninterval_steps = 0\n", "insitu.catalyst.interval_steps"},
      {"scripts = [\"s.py\"]\nlive_url = \"\"\n", "insitu.catalyst.live_url"},
      {"scripts = [\"s.py\"]\nscript = \"s.py\"\n", "insitu.catalyst.script"},
  };
  for (const auto& row : rows) {
    write_file(dir / "scene.toml", scene_with_catalyst(row.section));
    const fs::path out = dir / "out";
    expect_bad_input(run_cli("run " + (dir / "scene.toml").string() + " --out " + out.string()),
                     row.named, out, row.section);
  }
}

}  // namespace
}  // namespace dustlift
