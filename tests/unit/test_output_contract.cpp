// docs/output.md and the README say what a run writes; this test reads their tables and checks
// a run against them: the .vtr/.vtp arrays and field data, the series files and their CSV
// headers, the series.h5 root attributes and the files of the folder, exactly as listed.
#include <gtest/gtest.h>
#include <vtkAbstractArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLRectilinearGridReader.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "support/run_cli.hpp"
#include "support/shock_over_dust.hpp"
#include "support/snapshot_compare.hpp"

namespace fs = std::filesystem;
using dustlift::testing::fresh_dir;
using dustlift::testing::read_bytes;
using dustlift::testing::run_cli;
using dustlift::testing::run_command;
using dustlift::testing::write_file;

namespace {

using Row = std::vector<std::string>;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The first markdown table after the first line containing `heading` (header and separator
/// rows left out), as trimmed cells.
std::vector<Row> table_after(const std::string& text, const std::string& heading) {
  const auto lines = lines_of(text);
  std::size_t k = 0;
  while (k < lines.size() && lines[k].find(heading) == std::string::npos) ++k;
  EXPECT_LT(k, lines.size()) << "no '" << heading << "'";
  while (k < lines.size() && lines[k].rfind("|", 0) != 0) ++k;
  std::vector<Row> rows;
  for (k += 2; k < lines.size() && lines[k].rfind("|", 0) == 0; ++k) {
    Row row;
    std::stringstream cells(lines[k].substr(1));
    for (std::string cell; std::getline(cells, cell, '|');) {
      const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      row.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    rows.push_back(row);
  }
  return rows;
}

/// The `...` spans of a cell.
std::vector<std::string> code_spans(const std::string& cell) {
  std::vector<std::string> spans;
  const std::regex span("`([^`]+)`");
  for (auto it = std::sregex_iterator(cell.begin(), cell.end(), span); it != std::sregex_iterator();
       ++it)
    spans.push_back((*it)[1]);
  return spans;
}

std::map<std::string, int> arrays(vtkFieldData* data) {
  std::map<std::string, int> names;
  for (int k = 0; k < data->GetNumberOfArrays(); ++k)
    names[data->GetAbstractArray(k)->GetName()] =
        data->GetAbstractArray(k)->GetNumberOfComponents();
  return names;
}

/// Documented (name -> components) of a table whose first two cells are `name` and a count.
std::map<std::string, int> documented_arrays(const std::vector<Row>& rows) {
  std::map<std::string, int> names;
  for (const Row& r : rows) names[code_spans(r.at(0)).at(0)] = std::stoi(r.at(1));
  return names;
}

std::set<std::string> keys(const std::map<std::string, int>& m) {
  std::set<std::string> s;
  for (const auto& [k, v] : m) s.insert(k);
  return s;
}

/// A documented column list ("time_s, height_at_x<X>_m, ...") as a regex of the CSV header:
/// <...> stands for an identifier part, "..." repeats the column before it.
std::regex header_pattern(const std::string& documented) {
  std::string pattern;
  std::string previous;
  std::stringstream parts(documented);
  for (std::string part; std::getline(parts, part, ',');) {
    part = std::regex_replace(part, std::regex("^ +| +$"), "");
    if (part == "...") {
      pattern += "(," + previous + ")*";
      continue;
    }
    std::string token = std::regex_replace(part, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)");
    token = std::regex_replace(token, std::regex("<[^>]+>"), "[A-Za-z0-9_]+");
    pattern += (pattern.empty() ? "" : ",") + token;
    previous = token;
  }
  return std::regex(pattern);
}

std::string first_line(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  return line;
}

class OutputContract : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_dir("output_contract"));
    write_file(*dir_ / "scene.toml", dustlift::testing::kShockOverDust);
    // Every optional output on, so that every documented array and series is written.
    const auto r =
        run_cli("run " + (*dir_ / "scene.toml").string() + " --out " + (*dir_ / "out").string() +
                " --threads 1 --set coupling.added_mass=true --set output.parcel_fronts=true");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path out() { return *dir_ / "out"; }
  static std::string doc(const std::string& name) {
    return read_bytes(std::string(DUSTLIFT_SOURCE_DIR) + "/" + name);
  }
  static fs::path last(const std::string& kind) {
    return out() / "vtk" / (kind == "gas" ? "gas_000004.vtr" : "parcels_000004.vtp");
  }
  static fs::path* dir_;
};
fs::path* OutputContract::dir_ = nullptr;

}  // namespace

namespace {

/// The arrays of one VTK file against the documentation: the table after `heading` in
/// docs/output.md (exactly those arrays and components), the field-data table, and the
/// README row whose first cell names `readme_key` (the arrays it lists; `with_field_data`:
/// also the field arrays).
void expect_documented(vtkDataSet* data, vtkFieldData* arrays_of, const std::string& heading,
                       const std::string& readme_key, bool with_field_data) {
  const std::string output_md = read_bytes(std::string(DUSTLIFT_SOURCE_DIR) + "/docs/output.md");
  const auto documented = documented_arrays(table_after(output_md, heading));
  EXPECT_EQ(arrays(arrays_of), documented) << heading;
  std::set<std::string> field;
  for (const Row& r : table_after(output_md, "Field data of every"))
    field.insert(code_spans(r.at(0)).at(0));
  EXPECT_EQ(field.size(), 3u);
  EXPECT_EQ(keys(arrays(data->GetFieldData())), field);
  std::set<std::string> expected = keys(documented);
  if (with_field_data) expected.insert(field.begin(), field.end());
  std::size_t rows = 0;
  for (const Row& r : table_after(read_bytes(std::string(DUSTLIFT_SOURCE_DIR) + "/README.md"),
                                  "## What a run writes")) {
    if (r.at(0).find(readme_key) == std::string::npos) continue;
    ++rows;
    std::set<std::string> named;
    for (const auto& s : code_spans(r.at(1))) named.insert(s);
    EXPECT_EQ(named, expected) << "README row " << readme_key;
  }
  EXPECT_EQ(rows, 1u) << readme_key;
}

}  // namespace

TEST_F(OutputContract, GasFileHoldsExactlyTheDocumentedArraysAndFieldData) {
  vtkNew<vtkXMLRectilinearGridReader> reader;
  reader->SetFileName(last("gas").string().c_str());
  reader->Update();
  ASSERT_EQ(reader->GetOutput()->GetNumberOfCells(), 480);
  EXPECT_EQ(reader->GetOutput()->GetCellData()->GetNumberOfArrays(), 8);
  expect_documented(reader->GetOutput(), reader->GetOutput()->GetCellData(),
                    "### Gas: `vtk/gas_NNNNNN.vtr`", "gas.pvd", true);
}

TEST_F(OutputContract, ParcelFileHoldsExactlyTheDocumentedArraysAndFieldData) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(last("parcels").string().c_str());
  reader->Update();
  ASSERT_EQ(reader->GetOutput()->GetNumberOfPoints(), 2404);
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetNumberOfArrays(), 13);
  expect_documented(reader->GetOutput(), reader->GetOutput()->GetPointData(),
                    "### Parcels: `vtk/parcels_NNNNNN.vtp`", "parcels.pvd", false);
}

TEST_F(OutputContract, EverySeriesFileIsDocumentedWithItsColumns) {
  const auto rows = table_after(doc("docs/output.md"), "## Series");
  ASSERT_EQ(rows.size(), 12u);
  std::set<std::string> matched;
  for (const Row& r : rows) {
    const std::string file = code_spans(r.at(0)).at(0);
    const std::regex name(std::regex_replace(std::regex_replace(file, std::regex("\\."), "\\."),
                                             std::regex("<[^>]+>"), "[a-z0-9_]+"));
    const std::regex header = header_pattern(code_spans(r.at(1)).at(0));
    std::size_t found = 0;
    for (const auto& f : fs::directory_iterator(out() / "series")) {
      const std::string base = f.path().filename().string();
      if (!std::regex_match(base, name)) continue;
      ++found;
      matched.insert(base);
      EXPECT_TRUE(std::regex_match(first_line(f.path()), header))
          << base << ": " << first_line(f.path()) << "\n documented: " << r.at(1);
    }
    EXPECT_GE(found, 1u) << file << " is documented but not written";
  }
  for (const auto& f : fs::directory_iterator(out() / "series")) {
    if (f.path().extension() == ".csv") {
      EXPECT_TRUE(matched.count(f.path().filename().string())) << f.path() << " is not documented";
    }
  }
  // Two bands, the parcel fronts with their line of sight and force totals, the dust cloud, its
  // histogram and its entrainment.
  EXPECT_EQ(matched.size(), 13u);
  // The README names each series family.
  for (const Row& r : table_after(doc("README.md"), "## What a run writes")) {
    if (r.at(0).find("series/*.csv") == std::string::npos) continue;
    for (const auto& s : code_spans(r.at(1))) {
      if (s.find('_') == std::string::npos && s != "probes") continue;  // units and the like
      if (s.rfind("name_unit", 0) == 0 || s.find("_per_") != std::string::npos || s == "units")
        continue;
      const std::string csv = std::regex_replace(s, std::regex("<band>"), "surface") + ".csv";
      EXPECT_TRUE(fs::exists(out() / "series" / csv)) << "README names " << s;
    }
  }
}

TEST_F(OutputContract, SeriesH5HasTheDocumentedRootAttributesAndAGroupPerSeries) {
  std::string names;
  for (const Row& r : table_after(doc("docs/output.md"), "### `series/series.h5`"))
    names += (names.empty() ? "" : " ") + code_spans(r.at(0)).at(0);
  const fs::path script = *dir_ / "h5check.py";
  write_file(script, R"py(
import sys, h5py, glob, os
f = h5py.File(sys.argv[1] + "/series/series.h5", "r")
documented = set(sys.argv[2].split())
assert set(f.attrs.keys()) == documented, (sorted(f.attrs.keys()), sorted(documented))
csv = sorted(os.path.basename(p)[:-4] for p in glob.glob(sys.argv[1] + "/series/*.csv"))
assert sorted(f.keys()) == csv, (sorted(f.keys()), csv)
for name in f:
    columns = f[name].attrs["columns"].split(",")
    assert sorted(columns) == sorted(f[name].keys()), name
    for c in columns[1:]:
        assert f[name][c].dims[0][0].name == "/" + name + "/" + columns[0], (name, c)
print("ok", len(csv))
)py");
  const auto r = run_command("/usr/bin/python3 " + script.string() + " " + out().string() + " '" +
                             names + "'");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("ok 13"), std::string::npos) << r.output;
}

TEST_F(OutputContract, TheFolderHoldsTheDocumentedFiles) {
  // The listing of docs/output.md: every entry a run writes exists (figures and the state come
  // from the scripts).
  const std::string text = doc("docs/output.md");
  const auto lines = lines_of(text.substr(text.find("OUTDIR/\n")));
  std::size_t entries = 0;
  for (std::size_t k = 1; k < lines.size() && lines[k] != "```"; ++k) {
    std::string path = lines[k].substr(2, lines[k].find(' ', 2) - 2);
    if (path.rfind("figures/", 0) == 0 || path == "pressure_parcels.pvsm") continue;
    ++entries;
    path = std::regex_replace(path, std::regex("NNNNNN"), "000000");
    path = std::regex_replace(path, std::regex("<name>"), "shock_position");
    EXPECT_TRUE(fs::exists(out() / path)) << path;
  }
  EXPECT_EQ(entries, 9u);
  // And the README's table (catalyst/ only with [insitu.catalyst]: test_catalyst.cpp checks it).
  for (const Row& r : table_after(doc("README.md"), "## What a run writes")) {
    for (std::string path : code_spans(r.at(0))) {
      if (path.rfind("figures/", 0) == 0 || path == "pressure_parcels.pvsm" || path == "catalyst/")
        continue;
      path = std::regex_replace(std::regex_replace(path, std::regex("NNNNNN"), "000000"),
                                std::regex("\\*"), "shock_position");
      EXPECT_TRUE(fs::exists(out() / path)) << "README: " << path;
    }
  }
}
