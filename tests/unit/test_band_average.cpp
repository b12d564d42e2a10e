// Band-averaged force histories aligned to shock arrival: synthetic parcels with known
// forces and arrival times give known bin averages exactly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "insitu/band_average.hpp"
#include "tests/support/scratch_dir.hpp"

namespace dustlift {
namespace {

constexpr double kBin = 1e-6;  // s
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Parcels 0-3 start in the band [0, 0.1) x [0, 0.002); 4-5 start outside it; 6 is in the
/// band but never reached by the shock. Arrival (in bins): 0, 0, 2, 2.
struct Synthetic {
  std::vector<double> x0{0.01, 0.02, 0.05, 0.06, 0.2, 0.03, 0.04};
  std::vector<double> y0{0.001, 0.001, 0.0005, 0.0015, 0.001, 0.003, 0.001};
  std::vector<double> arrival{0.0, 0.0, 2 * kBin, 2 * kBin, 0.0, 0.0, kNaN};
  std::vector<double> y{1.0 / 1024, 2.0 / 1024, 3.0 / 1024, 4.0 / 1024, 9.0, 9.0, 9.0};
  std::vector<double> drag_x{-1, -1, -1, -1, 1e9, 1e9, 1e9};
  std::vector<double> drag_y{1, 3, 10, 20, 1e9, 1e9, 1e9};
  std::vector<double> contact_x = std::vector<double>(7), contact_y = std::vector<double>(7, 0.5);
  std::vector<double> pressure_x{0, 0, 0, 0, 1e9, 1e9, 1e9}, pressure_y{-2, -2, -2, -2, 1e9, 1e9, 1e9};
  std::vector<double> rel{100, 200, 300, 400, 1e9, 1e9, 1e9}, part{1, 1, 1, 1, 1e9, 1e9, 1e9},
      gas{50, 50, 50, 50, 1e9, 1e9, 1e9};

  BandParcelsView view(int output) {
    for (std::size_t k = 0; k < 7; ++k) contact_x[k] = output;  // contact x = output index
    BandParcelsView v;
    v.count = 7;
    v.initial_position = {x0, y0};
    v.y = y;
    v.arrival_time = arrival;
    v.force_drag = {drag_x, drag_y};
    v.force_contact = {contact_x, contact_y};
    v.force_pressure = {pressure_x, pressure_y};  // force_magnus absent: NaN columns
    v.relative_rotation = rel;
    v.particle_rotation = part;
    v.gas_rotation = gas;
    return v;
  }
};

BandAverageOptions options() {
  BandAverageOptions o;
  o.tau_min = 0.0;
  o.tau_max = 10 * kBin;
  o.bin_width = kBin;
  o.contact_window = 2 * kBin;
  return o;
}

TEST(BandAverage, KnownForcesAndArrivalsGiveKnownBinMeans) {
  Synthetic s;
  BandForceAccumulator acc(Band{"lower", 0.0, 0.1, 0.0, 0.002}, options());
  ASSERT_EQ(acc.bins(), 10u);
  for (int m = 0; m < 6; ++m) acc.add(s.view(m), (m + 0.5) * kBin);  // outputs mid-bin
  using A = BandForceAccumulator;
  // Bin b holds parcels with arrival n if b + n <= 5: all four for b <= 3, two for b = 4, 5.
  for (std::size_t b = 0; b < 10; ++b) {
    SCOPED_TRACE("bin " + std::to_string(b));
    const std::size_t expected_samples = b <= 3 ? 4 : (b <= 5 ? 2 : 0);
    ASSERT_EQ(acc.samples(b), expected_samples);
    EXPECT_DOUBLE_EQ(acc.bin_center(b), (b + 0.5) * kBin);
    if (expected_samples == 0) {
      EXPECT_TRUE(std::isnan(acc.mean(A::kDragY, b)));
      continue;
    }
    EXPECT_EQ(acc.mean(A::kDragY, b), b <= 3 ? 8.5 : 2.0);
    EXPECT_EQ(acc.mean(A::kDragX, b), -1.0);
    EXPECT_EQ(acc.mean(A::kHeight, b), b <= 3 ? 2.5 / 1024 : 1.5 / 1024);
    EXPECT_EQ(acc.mean(A::kPressureY, b), -2.0);
    EXPECT_EQ(acc.mean(A::kRelativeRotation, b), b <= 3 ? 250.0 : 150.0);
    EXPECT_EQ(acc.mean(A::kGasRotation, b), 50.0);
    EXPECT_TRUE(std::isnan(acc.mean(A::kMagnusY, b)));
    // Contact x = output index m = b + n: per bin (b + (b + 2)) / 2 = b + 1 for b <= 3.
    EXPECT_EQ(acc.mean(A::kContactX, b), b <= 3 ? b + 1.0 : static_cast<double>(b));
    EXPECT_EQ(acc.mean(A::kContactY, b), 0.5);
    // 2-bin windows: {0,0,1,1,2,2,3,3} -> 1.5; {2,2,3,3,4,4,5,5} -> 3.5; {4,4,5,5} -> 4.5.
    const double window[] = {1.5, 1.5, 3.5, 3.5, 4.5, 4.5};
    EXPECT_EQ(acc.contact_window_mean(0, b), window[b]);
    EXPECT_EQ(acc.contact_window_mean(1, b), 0.5);
  }
}

TEST(BandAverage, TableHasOneRowPerFilledBinAndIsWrittenAsCsv) {
  Synthetic s;
  const auto dir = testing::scratch_dir("band_series", false);
  BandForceSeries series({Band{"lower", 0.0, 0.1, 0.0, 0.002}, Band{"upper", 0.0, 0.1, 0.002, 0.004}},
                         options());
  const SeriesSink sink(dir.string());
  for (int m = 0; m < 6; ++m) {
    series.add(s.view(m), (m + 0.5) * kBin);
    series.write(sink);  // rewritten whole at each output
  }
  const SeriesTable lower = series.accumulators()[0].table();
  EXPECT_EQ(lower.rows(), 6u);
  EXPECT_EQ(lower.header(0), "tau_s");
  EXPECT_EQ(lower.header(5), "drag_x_N");
  EXPECT_EQ(lower.column(6)[0], 8.5);  // drag_y
  // Parcel 5 starts at y0 = 3 mm (upper band): in every bin from 0 to 5.
  const SeriesTable upper = series.accumulators()[1].table();
  EXPECT_EQ(upper.rows(), 6u);
  std::ifstream csv(dir / "series" / "forces_lower.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("tau_s,samples_1,height_m,contact_x_N,contact_y_N,drag_x_N", 0), 0u);
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 6);
  EXPECT_TRUE(std::filesystem::exists(dir / "series" / "forces_upper.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "series" / "series.h5"));
}

TEST(BandAverage, ArrivalIsTheFirstSampleWhenTheShockStoodAtOrBeyondTheInitialX) {
  ShockTrajectory t;
  t.record(1e-5, 0.15);
  t.record(2e-5, 0.25);
  t.record(3e-5, kNaN);   // no shock found: ignored
  t.record(4e-5, 0.22);   // a dip does not move the reach back
  EXPECT_EQ(t.arrival_time(0.0), 1e-5);
  EXPECT_EQ(t.arrival_time(0.1), 1e-5);
  EXPECT_EQ(t.arrival_time(0.15), 1e-5);
  EXPECT_EQ(t.arrival_time(0.2), 2e-5);
  EXPECT_EQ(t.arrival_time(0.25), 2e-5);
  EXPECT_TRUE(std::isnan(t.arrival_time(0.3)));
  EXPECT_EQ(t.reach(), 0.25);
  EXPECT_EQ(t.times().size(), 2u);
  // Only parcels in a band get an arrival time.
  const std::vector<Band> bands{{"b", 0.05, 0.3, 0.0, 1.0}};
  const std::vector<double> x0{0.0, 0.1, 0.2, 0.3}, y0{0.5, 0.5, 0.5, 0.5};
  std::vector<double> arrival(4, 0.0);
  band_arrival_times(t, bands, x0, y0, arrival);
  EXPECT_TRUE(std::isnan(arrival[0]));
  EXPECT_EQ(arrival[1], 1e-5);
  EXPECT_EQ(arrival[2], 2e-5);
  EXPECT_TRUE(std::isnan(arrival[3]));
  EXPECT_THROW(t.record(0.0, 0.5), std::invalid_argument);
}

TEST(BandAverage, PositionsJumpingBeyondTheAllowedAdvanceAreIgnoredAndCounted) {
  ShockTrajectory t;
  t.record(1e-6, 0.100, 0.002);  // the first sample: no reach to compare with
  t.record(2e-6, 0.101, 0.002);
  t.record(3e-6, 0.180, 0.002);  // a pulse 79 mm ahead: ignored
  t.record(4e-6, 0.1025, 0.002);
  t.record(5e-6, 0.1045, 0.002);  // 2 mm beyond the reach: still a shock
  EXPECT_EQ(t.ignored_jumps(), 1u);
  EXPECT_EQ(t.reach(), 0.1045);
  EXPECT_EQ(t.arrival_time(0.102), 4e-6);
  EXPECT_EQ(t.times().size(), 4u);
}

}  // namespace
}  // namespace dustlift
