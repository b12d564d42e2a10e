// Series sink: CSV (header "name_unit", appended per output) and series.h5 (group per
// series, dataset per column with units) stay equal to the table after repeated writes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "insitu/series_table.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

std::filesystem::path fresh_dir(const std::string& name) { return testing::scratch_dir("series_" + name); }

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

void expect_tables_equal(const SeriesTable& a, const SeriesTable& b) {
  ASSERT_EQ(a.columns().size(), b.columns().size());
  ASSERT_EQ(a.rows(), b.rows());
  for (std::size_t c = 0; c < a.columns().size(); ++c) {
    EXPECT_EQ(a.columns()[c].name, b.columns()[c].name);
    EXPECT_EQ(a.columns()[c].unit, b.columns()[c].unit);
    for (std::size_t r = 0; r < a.rows(); ++r) {
      if (std::isnan(a.column(c)[r])) {
        EXPECT_TRUE(std::isnan(b.column(c)[r]));
      } else {
        EXPECT_EQ(a.column(c)[r], b.column(c)[r]) << a.header(c) << " row " << r;
      }
    }
  }
}

TEST(SeriesSink, CsvIsAppendedPerOutputAndRoundTripsExactly) {
  const auto dir = fresh_dir("csv");
  SeriesSink sink(dir.string());
  SeriesTable t("surface_height", {{"time", "s"}, {"x", "m"}, {"height", "m"}});
  for (int output = 0; output < 3; ++output) {
    for (int i = 0; i < 4; ++i)
      t.append_row(std::vector{1e-5 * output, 0.1 * i + 1.0 / 3.0, std::nan("") });
    t.append_row(std::vector{1e-5 * output, 0.7, 2.0e-3 / 7.0});
    sink.write(t);
  }
  const auto rows = read_csv(sink.csv_path(t));
  ASSERT_EQ(rows.size(), 1u + 15u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"time_s", "x_m", "height_m"}));
  for (std::size_t r = 0; r < 15; ++r) {
    EXPECT_EQ(std::stod(rows[r + 1][0]), t.column(0)[r]);
    EXPECT_EQ(std::stod(rows[r + 1][1]), t.column(1)[r]);
    if (r % 5 == 4) EXPECT_EQ(std::stod(rows[r + 1][2]), t.column(2)[r]);
    else EXPECT_EQ(rows[r + 1][2], "nan");
  }
  expect_tables_equal(t, read_series_h5(sink.h5_path(), "surface_height"));
}

TEST(SeriesSink, ClearedTableRewritesTheCsvAndTheGroup) {
  const auto dir = fresh_dir("clear");
  SeriesSink sink(dir.string());
  SeriesTable t("forces_top", {{"tau", "s"}, {"drag_y", "N"}});
  for (int k = 0; k < 10; ++k) t.append_row(std::vector{k * 1e-6, k * 2.0});
  sink.write(t);
  t.clear();
  for (int k = 0; k < 4; ++k) t.append_row(std::vector{k * 1e-6, -k * 1.0});
  sink.write(t);
  EXPECT_EQ(read_csv(sink.csv_path(t)).size(), 5u);
  expect_tables_equal(t, read_series_h5(sink.h5_path(), "forces_top"));
}

TEST(SeriesSink, RepeatedWritesKeepEveryGroupAndTheFileSmall) {
  const auto dir = fresh_dir("repeat");
  SeriesSink sink(dir.string());
  SeriesTable shock("shock_position", {{"time", "s"}, {"x", "m"}});
  SeriesTable stations("surface_height_stations",
                       {{"time", "s"}, {"height_at_x0p1", "m"}, {"height_at_x0p2", "m"}});
  std::uintmax_t size_after_10 = 0;
  for (int output = 0; output < 200; ++output) {
    shock.append_row(std::vector{output * 1e-6, 0.01 + output * 1e-3});
    stations.append_row(std::vector{output * 1e-6, 1e-3 * output, std::nan("")});
    sink.write(shock);
    sink.write(stations);
    if (output == 10) size_after_10 = std::filesystem::file_size(sink.h5_path());
  }
  expect_tables_equal(shock, read_series_h5(sink.h5_path(), "shock_position"));
  expect_tables_equal(stations, read_series_h5(sink.h5_path(), "surface_height_stations"));
  // Resized datasets reuse their chunks: 200 rewrites must not grow the file 200-fold.
  EXPECT_LT(std::filesystem::file_size(sink.h5_path()), 3 * size_after_10);
}

TEST(SeriesSink, AnOutputWritesOnlyTheRowsAddedSinceTheLastAndACopyWholly) {
  // A profile series adds thousands of rows per output: rewriting the whole group each time
  // cost the square of the run's length. A value changed in the file behind the sink's back
  // shows which rows a write touched.
  const auto dir = fresh_dir("append");
  SeriesSink sink(dir.string());
  SeriesTable t("dust_entrainment", {{"time", "s"}, {"x", "m"}});
  for (int k = 0; k < 5; ++k) t.append_row(std::vector{0.0, 0.1 * k});
  sink.write(t);
  SeriesTable changed("dust_entrainment", {{"time", "s"}, {"x", "m"}});
  for (int k = 0; k < 5; ++k) changed.append_row(std::vector{0.0, k == 2 ? -7.0 : 0.1 * k});
  write_series_h5(sink.h5_path(), changed);
  for (int k = 0; k < 5; ++k) t.append_row(std::vector{1e-5, 0.1 * k});
  sink.write(t);
  SeriesTable back = read_series_h5(sink.h5_path(), "dust_entrainment");
  ASSERT_EQ(back.rows(), 10u);
  EXPECT_EQ(back.column(1)[2], -7.0);  // written at the first output, not again
  for (std::size_t r = 5; r < 10; ++r) {
    EXPECT_EQ(back.column(0)[r], 1e-5);
    EXPECT_EQ(back.column(1)[r], 0.1 * static_cast<double>(r - 5));
  }
  // A checkpoint's copy (fewer rows than the file holds, as after a run killed past its
  // last checkpoint) replaces the group's rows whole.
  t.assign({{0.0, 0.0, 0.0}, {0.0, 0.1, 0.2}});
  sink.write(t);
  expect_tables_equal(t, read_series_h5(sink.h5_path(), "dust_entrainment"));
  t.append_row(std::vector{1e-5, 0.5});
  sink.write(t);
  expect_tables_equal(t, read_series_h5(sink.h5_path(), "dust_entrainment"));
}

TEST(SeriesSink, ChangedColumnsReplaceTheGroupAndABrokenFileIsRecreated) {
  const auto dir = fresh_dir("broken");
  const auto path = (dir / "series" / "series.h5").string();
  SeriesTable a("stations", {{"time", "s"}, {"height_at_x0p1", "m"}});
  a.append_row(std::vector{0.0, 1.0});
  write_series_h5(path, a);
  SeriesTable b("stations", {{"time", "s"}, {"height_at_x0p3", "m"}, {"height_at_x0p4", "m"}});
  b.append_row(std::vector{0.0, 2.0, 3.0});
  write_series_h5(path, b);
  expect_tables_equal(b, read_series_h5(path, "stations"));
  { std::ofstream garbage(path, std::ios::trunc); garbage << "not an HDF5 file"; }
  write_series_h5(path, a);
  expect_tables_equal(a, read_series_h5(path, "stations"));
  EXPECT_THROW(read_series_h5(path, "missing"), std::runtime_error);
}

TEST(SeriesNames, HeadersAreIdentifiersThatNumpyAndPandasKeep) {
  EXPECT_EQ(csv_unit_token("m/s"), "m_per_s");
  EXPECT_EQ(csv_unit_token("rad/s"), "rad_per_s");
  EXPECT_EQ(csv_unit_token("1/s"), "per_s");
  EXPECT_EQ(csv_unit_token("kg/m^3"), "kg_per_m3");
  EXPECT_EQ(csv_unit_token("N m"), "N_m");
  EXPECT_EQ(csv_unit_token("1"), "1");
  EXPECT_EQ(number_in_identifier(0.025), "0p025");
  EXPECT_EQ(number_in_identifier(-0.01), "m0p01");
  EXPECT_EQ(number_in_identifier(0.1), "0p1");
  EXPECT_EQ(number_in_identifier(2.0), "2");
  EXPECT_EQ(SeriesTable("near_layer", {{"time", "s"}, {"u", "m/s"}}).header(1), "u_m_per_s");
  EXPECT_THROW(SeriesTable("stations", {{"time", "s"}, {"height_at_x0.1", "m"}}), std::invalid_argument);
  EXPECT_THROW(SeriesTable("forces-top", {{"tau", "s"}}), std::invalid_argument);
}

}  // namespace
}  // namespace dustlift
