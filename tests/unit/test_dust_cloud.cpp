// The dust cloud of known parcels over a known concentration field, every number worked out by
// hand (dust_cloud.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "insitu/dust_cloud.hpp"
#include "insitu/entrainment.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/scene/cloud_filter.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"
#include "support/shock_over_dust.hpp"

namespace dustlift {
namespace {

// Flow-grid cells 1 mm square: x faces 0..4 mm, y faces -1..2 mm; the layer's top at y = 0.
const std::vector<double> kXFaces{0.0, 1e-3, 2e-3, 3e-3, 4e-3};
const std::vector<double> kYFaces{-1e-3, 0.0, 1e-3, 2e-3};

// Five parcels: 0 rests in the layer, 4 sits 50 um above the top (below the 100 um lift
// height), 1-3 are lifted at 0.5, 1.5 and 0.2 mm. Parcels 1 and 2 hold 50 um particles
// (fines), the others 100 um ones.
struct Parcels {
  std::vector<double> x{0.5e-3, 1.5e-3, 2.5e-3, 2.6e-3, 3.5e-3};
  std::vector<double> y{-0.5e-3, 0.5e-3, 1.5e-3, 0.2e-3, 0.05e-3};
  std::vector<double> mass{2e-8, 5e-8, 3e-8, 1.2e-8, 4e-8};
  std::vector<double> temperature{300.0, 400.0, 500.0, 350.0, 320.0};
  std::vector<double> size_class{0.0, 0.0, 1.0, 1.0, 1.0};
  std::vector<double> diameter{100e-6, 50e-6, 50e-6, 100e-6, 100e-6};
  CloudParcels view() const { return {x, y, mass, temperature, size_class, diameter}; }
};

// The filter's boxes are 1 mm square (the flow grid's cells), sliding over a lattice of 1/3 mm
// sub-cells (k = 3, few enough to count by hand) aligned at x = 0, y = 0, over a channel 4 mm
// long and 2 mm high above the layer: 12 x 6 sub-cells, 10 x 4 box positions.
DustCloudOptions options() {
  DustCloudOptions o;
  o.layer_top = 0.0;
  o.lift_height = 1e-4;
  o.top_concentration = 1e-3;
  o.classes = 2;
  o.filter_width = 1e-3;
  o.filter_subcells = 3;
  o.x_origin = 0.0;
  o.x_start = 0.0;
  o.x_end = 4e-3;
  o.y_end = 2e-3;
  o.explosible_lower = 0.02;
  o.explosible_upper = 1.0;
  o.fines_diameter = 75e-6;
  o.heights = {0.4e-3, 1e-3};
  return o;
}

// Row 0 is the layer (ignored), row 1 holds two dusty cells, row 2 a trace at the top level.
std::vector<double> concentration(double top_row_trace) {
  return {500.0, 500.0, 500.0,         500.0,  //
          0.0,   0.06,  0.2,           5e-4,   //
          0.0,   0.0,   top_row_trace, 0.0};
}

TEST(DustCloud, KnownParcelsGiveTheirMassHeightsAndTemperatures) {
  const Parcels p;
  const std::vector<double> c = concentration(2e-3);
  DustCloudScratch scratch;
  const DustCloud cloud = dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch);
  EXPECT_DOUBLE_EQ(cloud.all.lifted_mass, 9.2e-8);
  EXPECT_DOUBLE_EQ(cloud.all.resting_mass, 6e-8);
  // Heights sorted 0.2 (1.2), 0.5 (5), 1.5 mm (3): 4.6 of 9.2 reached at 0.5 mm, 8.28 at 1.5.
  EXPECT_EQ(cloud.all.height_p50, 0.5e-3);
  EXPECT_EQ(cloud.all.height_p90, 1.5e-3);
  EXPECT_EQ(cloud.all.height_p99, 1.5e-3);
  EXPECT_EQ(cloud.all.temperature_max, 500.0);
  EXPECT_DOUBLE_EQ(cloud.all.temperature_mean, (5.0 * 400.0 + 3.0 * 500.0 + 1.2 * 350.0) / 9.2);
  ASSERT_EQ(cloud.per_class.size(), 2u);
  EXPECT_EQ(cloud.per_class[0].lifted_mass, 5e-8);
  EXPECT_EQ(cloud.per_class[0].resting_mass, 2e-8);
  EXPECT_EQ(cloud.per_class[0].height_p50, 0.5e-3);
  EXPECT_EQ(cloud.per_class[0].temperature_mean, 400.0);
  EXPECT_DOUBLE_EQ(cloud.per_class[1].lifted_mass, 4.2e-8);
  EXPECT_EQ(cloud.per_class[1].resting_mass, 4e-8);
  EXPECT_EQ(cloud.per_class[1].height_p50, 1.5e-3);  // 1.2 of 4.2 at 0.2 mm, the rest at 1.5
  // Lifted mass per column: 5 in column 1, 4.2 in column 2: the first (most downstream)
  // lifted column is 2, the densest 1.
  EXPECT_EQ(cloud.first_lifted_x, 2.5e-3);
  EXPECT_EQ(cloud.densest_lifted_x, 1.5e-3);
  // Above 0.4 mm: parcels 1 and 2; above 1 mm: parcel 2.
  ASSERT_EQ(cloud.mass_above.size(), 2u);
  EXPECT_DOUBLE_EQ(cloud.mass_above[0], 8e-8);
  EXPECT_EQ(cloud.mass_above[1], 3e-8);
}

// a and b equal to round-off (sums of shares divided by their boxes' counts).
void expect_close(double a, double b) {
  EXPECT_NEAR(a, b, 1e-12 * std::abs(b)) << a << " vs " << b;
}

TEST(DustCloud, KnownParcelsGiveTheFilteredConcentrationItsQuantumAndTheBandsMass) {
  const Parcels p;
  const std::vector<double> c = concentration(2e-3);
  DustCloudScratch scratch;
  const FilteredCloud f = dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch).filtered;
  // Boxes of 1e-6 m^2: the largest parcel (5e-8 kg/m, parcel 1, resting or not) alone in one
  // is 0.05 kg/m^3.
  EXPECT_DOUBLE_EQ(f.quantum, 0.05);
  // Lifted dust in sub-cells (i, j): parcel 1 in (4, 1), parcel 2 in (7, 4), parcel 3 in
  // (7, 0). No box of 3 x 3 sub-cells holds two of them: every box holding parcel 1 reads
  // 0.05 kg/m^3, parcel 2's 0.03, parcel 3's 0.012. Parcel 1 lies in the boxes at x positions
  // 2-4 and y positions 0-1 (6 boxes, each its share 5e-8 / 6 and area share / 0.05 = 1/6 mm^2),
  // so it adds its mass and one box's area, 1 mm^2; so do the others. The resting parcels 0
  // and 4 are the bed: not counted.
  expect_close(f.cloud_area, 3e-6);
  expect_close(f.cloud_concentration, 9.2e-8 / 3e-6);
  // The band [0.02, 1] kg/m^3 holds the first two: 8e-8 kg/m on 2e-6 m^2, 0.04 kg/m^3, over
  // the boxes from parcel 1's first (x from 2/3 mm) to parcel 2's last (to 10/3 mm).
  expect_close(f.explosible_mass, 8e-8);
  expect_close(f.explosible_area, 2e-6);
  expect_close(f.explosible_concentration, 0.04);
  EXPECT_DOUBLE_EQ(f.explosible_x_min, 2e-3 / 3.0);
  EXPECT_DOUBLE_EQ(f.explosible_x_max, 10e-3 / 3.0);
  // Fines: parcels 1 and 2 (50 um), both lifted, both in the band.
  EXPECT_DOUBLE_EQ(f.fines_lifted_mass, 8e-8);
  expect_close(f.fines_explosible_mass, 8e-8);
  expect_close(f.fines_explosible_concentration, 0.04);
  expect_close(f.fines_cloud_concentration, 8e-8 / 3e-6);
  // Histogram, 10 bins per decade from 1e-4 kg/m^3: 0.012 in bin 20 ([0.01, 0.0126)), 0.03
  // in bin 24 ([0.0251, 0.0316)), 0.05 in bin 26 ([0.0398, 0.0501)).
  EXPECT_DOUBLE_EQ(histogram_edge(20), 0.01);
  expect_close(f.histogram_mass[20], 1.2e-8);
  expect_close(f.histogram_mass[24], 3e-8);
  expect_close(f.histogram_mass[26], 5e-8);
  EXPECT_EQ(f.histogram_fines[20], 0.0);
  expect_close(f.histogram_fines[24], 3e-8);
  expect_close(f.histogram_area[24], 1e-6);
  double total = 0.0;
  for (double m : f.histogram_mass) total += m;
  expect_close(total, 9.2e-8);  // every lifted parcel's shares in the bins

  // A band whose lower edge lies between the two parcels' concentrations parts them.
  DustCloudOptions o = options();
  o.explosible_lower = 0.04;
  const FilteredCloud g = dust_cloud(p.view(), {kXFaces, kYFaces, c}, o, scratch).filtered;
  expect_close(g.explosible_mass, 5e-8);
  expect_close(g.explosible_area, 1e-6);
  EXPECT_DOUBLE_EQ(g.explosible_x_min, 2e-3 / 3.0);
  EXPECT_DOUBLE_EQ(g.explosible_x_max, 7e-3 / 3.0);
}

// What the sliding box is for: two parcels of 3e-8 kg/m, 0.03 kg/m^3 each alone in a box,
// part as one drifts downstream, and the band [0.05, 1] (which only the boxes holding both
// reach) loses their mass in steps of the lattice instead of all at once.
TEST(DustCloud, TheBandLosesAPairOfParcelsStepByStepAsTheyPart) {
  Parcels p;
  p.x = {0.5e-3, 1.5e-3, 1.8e-3};  // 0 rests; 1 and 2 lifted in sub-cells (4, 0) and (5, 0)
  p.y = {-0.5e-3, 0.2e-3, 0.2e-3};
  p.mass = {2e-8, 3e-8, 3e-8};
  p.temperature = {300.0, 300.0, 300.0};
  p.size_class = {0.0, 0.0, 0.0};
  p.diameter = {100e-6, 100e-6, 100e-6};
  DustCloudOptions o = options();
  o.explosible_lower = 0.05;
  const std::vector<double> c = concentration(2e-3);
  DustCloudScratch scratch;
  // Both hold only the lowest box row (y position 0). Boxes at x positions 2-5: 2 holds
  // parcel 1 (0.03 kg/m^3), 3 and 4 both (0.06), 5 parcel 2 (0.03). Each parcel is shared by
  // 3 boxes (1e-8 kg/m each): the band's mass is 4e-8 on 2 x 2e-8 / 0.06 = 2/3 mm^2 at 0.06,
  // over x from 1 to 7/3 mm; the cloud 6e-8 on 4/3 mm^2.
  FilteredCloud f = dust_cloud(p.view(), {kXFaces, kYFaces, c}, o, scratch).filtered;
  expect_close(f.explosible_mass, 4e-8);
  expect_close(f.explosible_area, 2e-6 / 3.0);
  expect_close(f.explosible_concentration, 0.06);
  EXPECT_DOUBLE_EQ(f.explosible_x_min, 1e-3);
  EXPECT_DOUBLE_EQ(f.explosible_x_max, 7e-3 / 3.0);
  expect_close(f.cloud_area, 4e-6 / 3.0);
  expect_close(f.cloud_concentration, 0.045);
  // Parcel 2 one sub-cell on, in (6, 0): only box 4 holds both, 2e-8 on 1/3 mm^2.
  p.x[2] = 2.1e-3;
  f = dust_cloud(p.view(), {kXFaces, kYFaces, c}, o, scratch).filtered;
  expect_close(f.explosible_mass, 2e-8);
  expect_close(f.explosible_area, 1e-6 / 3.0);
  // In (7, 0): no box holds both, the band is empty.
  p.x[2] = 2.5e-3;
  f = dust_cloud(p.view(), {kXFaces, kYFaces, c}, o, scratch).filtered;
  EXPECT_EQ(f.explosible_mass, 0.0);
  EXPECT_TRUE(std::isnan(f.explosible_concentration));
  expect_close(f.cloud_area, 2e-6);  // two boxes' worth: each parcel alone
}

TEST(DustCloud, BoxesCutByTheChannelCountTheirAreaInsideItAndWiderBoxesLowerTheQuantum) {
  const Parcels p;
  const std::vector<double> c = concentration(2e-3);
  DustCloudScratch scratch;
  // 1.5 mm of channel above the layer: 5 sub-cell rows, the last 1/6 mm high. Parcel 2 (row 4)
  // lies in the top box row only (rows 2-4, 5/6 mm high): it alone makes 3e-8 / (5/6 mm^2) =
  // 0.036 kg/m^3, which a band of [0.033, 0.04] holds alone (parcel 1's boxes read 0.05,
  // parcel 3's 0.012): its mass on 5/6 mm^2.
  DustCloudOptions o = options();
  o.y_end = 1.5e-3;
  o.explosible_lower = 0.033;
  o.explosible_upper = 0.04;
  const FilteredCloud f = dust_cloud(p.view(), {kXFaces, kYFaces, c}, o, scratch).filtered;
  expect_close(f.explosible_mass, 3e-8);
  expect_close(f.explosible_area, 5e-6 / 6.0);
  expect_close(f.explosible_concentration, 0.036);
  // Boxes of 2 mm (sub-cells of 2/3 mm, 6 x 3; one box row, 4 positions along x): the quantum
  // falls fourfold. Parcel 1 lies in sub-cell column 2, parcels 2 and 3 in column 3: box 0
  // (columns 0-2) holds parcel 1, 5e-8 / 4e-6 = 0.0125 kg/m^3; boxes 1 and 2 all three,
  // 0.023; box 3 parcels 2 and 3, 0.0105. Each parcel is shared by three boxes, so box 0's
  // share is 5e-8 / 3, boxes 1 and 2 9.2e-8 / 3, box 3 4.2e-8 / 3, and each share's area is
  // a third of its box's, 4/3 mm^2.
  o = options();
  o.filter_width = 2e-3;
  o.explosible_lower = 0.01;
  const FilteredCloud w = dust_cloud(p.view(), {kXFaces, kYFaces, c}, o, scratch).filtered;
  EXPECT_DOUBLE_EQ(w.quantum, 0.0125);
  expect_close(w.explosible_area, 16e-6 / 3.0);
  expect_close(w.explosible_mass, 9.2e-8);
  expect_close(w.explosible_concentration, 9.2e-8 / (16e-6 / 3.0));
  // A band from 0.02 kg/m^3 holds boxes 1 and 2: x from 2/3 to 10/3 mm.
  o.explosible_lower = 0.02;
  const FilteredCloud b = dust_cloud(p.view(), {kXFaces, kYFaces, c}, o, scratch).filtered;
  expect_close(b.explosible_mass, 2.0 * 9.2e-8 / 3.0);
  expect_close(b.explosible_area, 8e-6 / 3.0);
  expect_close(b.explosible_concentration, 0.023);
  EXPECT_DOUBLE_EQ(b.explosible_x_min, 2e-3 / 3.0);
  EXPECT_DOUBLE_EQ(b.explosible_x_max, 10e-3 / 3.0);
}

// At the shipped lattice (k = 9): one parcel alone reads the quantum over one box's area
// wherever it lies, in the middle of the channel or against the layer top (where fewer
// boxes hold it, each a larger share).
TEST(DustCloud, AParcelAloneReadsTheQuantumOverOneBoxWhereverItLies) {
  DustCloudOptions o = options();
  o.filter_subcells = kFilterSubcells;
  o.classes = 1;
  const std::vector<double> c = concentration(2e-3);
  DustCloudScratch scratch;
  for (const double y : {1.0e-3, 0.15e-3, 1.95e-3}) {
    for (const double x : {2.0e-3, 0.01e-3, 3.99e-3}) {
      const std::vector<double> px{x}, py{y}, m{4e-8}, t{300.0};
      const FilteredCloud f =
          dust_cloud({px, py, m, t, {}, {}}, {kXFaces, kYFaces, c}, o, scratch).filtered;
      expect_close(f.explosible_mass, 4e-8);
      expect_close(f.explosible_area, 1e-6);
      expect_close(f.explosible_concentration, 0.04);
      expect_close(f.cloud_area, 1e-6);
    }
  }
}

// The shares add up to the lifted mass, for parcels anywhere in a channel whose ends fall
// between the lattice's lines (the boxes there are cut by the channel): every histogram
// adds up (mass, fines, area) and the band holds a part of the cloud.
TEST(DustCloud, TheSharesAddUpToTheLiftedMass) {
  DustCloudOptions o = options();
  o.filter_subcells = kFilterSubcells;
  o.classes = 1;
  o.x_start = -0.37e-3;
  o.x_end = 3.93e-3;
  o.y_end = 1.71e-3;
  o.explosible_lower = 0.05;
  o.explosible_upper = 0.2;
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> ux(-0.37e-3, 3.93e-3), uy(-0.2e-3, 1.71e-3),
      um(1e-9, 1e-8), ud(20e-6, 120e-6);
  const std::size_t n = 300;
  std::vector<double> x(n), y(n), m(n), t(n, 300.0), d(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = ux(random);
    y[i] = uy(random);
    m[i] = um(random);
    d[i] = ud(random);
  }
  const std::vector<double> c = concentration(2e-3);
  DustCloudScratch scratch;
  const DustCloud cloud = dust_cloud({x, y, m, t, {}, d}, {kXFaces, kYFaces, c}, o, scratch);
  const FilteredCloud& f = cloud.filtered;
  double mass = 0.0, fines = 0.0, area = 0.0;
  for (int k = 0; k < kHistogramBins; ++k) {
    mass += f.histogram_mass[static_cast<std::size_t>(k)];
    fines += f.histogram_fines[static_cast<std::size_t>(k)];
    area += f.histogram_area[static_cast<std::size_t>(k)];
  }
  ASSERT_GT(cloud.all.lifted_mass, 0.0);
  expect_close(mass, cloud.all.lifted_mass);
  expect_close(fines, f.fines_lifted_mass);
  expect_close(area, f.cloud_area);
  expect_close(f.cloud_concentration * f.cloud_area, cloud.all.lifted_mass);
  EXPECT_GT(f.explosible_mass, 0.0);
  EXPECT_LT(f.explosible_mass, cloud.all.lifted_mass);
  EXPECT_GE(f.explosible_concentration, o.explosible_lower);
  EXPECT_LE(f.explosible_concentration, o.explosible_upper);
}

TEST(DustCloud, KnownConcentrationGivesTheTop) {
  const Parcels p;
  DustCloudScratch scratch;
  const std::vector<double> c = concentration(2e-3);
  const DustCloud cloud = dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch);
  EXPECT_EQ(cloud.cloud_top, 2e-3);  // row 2 reaches the top level: its upper face
  // Below the level in row 2 the top falls to row 1's upper face.
  const std::vector<double> thin = concentration(9e-4);
  EXPECT_EQ(dust_cloud(p.view(), {kXFaces, kYFaces, thin}, options(), scratch).cloud_top, 1e-3);
}

TEST(DustCloud, NothingLiftedGivesZeroMassAndNaNHeights) {
  Parcels p;
  p.y = {-0.5e-3, -0.5e-3, -0.5e-3, -0.5e-3, -0.5e-3};
  std::vector<double> c(12, 0.0);
  DustCloudScratch scratch;
  const DustCloud cloud = dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch);
  EXPECT_EQ(cloud.all.lifted_mass, 0.0);
  EXPECT_DOUBLE_EQ(cloud.all.resting_mass, 15.2e-8);
  EXPECT_TRUE(std::isnan(cloud.all.height_p50));
  EXPECT_TRUE(std::isnan(cloud.all.temperature_mean));
  EXPECT_TRUE(std::isnan(cloud.first_lifted_x));
  EXPECT_EQ(cloud.filtered.explosible_area, 0.0);
  EXPECT_EQ(cloud.filtered.explosible_mass, 0.0);
  EXPECT_TRUE(std::isnan(cloud.filtered.explosible_x_min));
  EXPECT_TRUE(std::isnan(cloud.filtered.explosible_concentration));
  EXPECT_TRUE(std::isnan(cloud.filtered.cloud_concentration));
  EXPECT_EQ(cloud.cloud_top, 0.0);
}

TEST(DustCloud, AClassOutsideTheLayersClassesIsRefused) {
  Parcels p;
  p.size_class[2] = 2.0;
  std::vector<double> c(12, 0.0);
  DustCloudScratch scratch;
  EXPECT_THROW(dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch),
               std::invalid_argument);
}

TEST(DustCloud, AQuantumAboveATenthOfTheLowerLimitIsWarnedAbout) {
  DustCloudOptions o = options();
  o.explosible_lower = 0.05;
  EXPECT_TRUE(quantum_warning(0.005, o).empty());
  const std::string w = quantum_warning(0.05, o);  // 1 mm cells; a tenth needs sqrt(10) mm
  EXPECT_NE(w.find("output.cloud_filter_width"), std::string::npos) << w;
  EXPECT_NE(w.find("100 %"), std::string::npos) << w;
  EXPECT_NE(w.find("0.00316 m, more than the 0.002 m of channel above the layer"),
            std::string::npos)
      << w;
}

TEST(WeightedQuantile, ReachesTheShareAtTheFirstValueThatCompletesIt) {
  const std::vector<double> h{1.5, 0.2, 0.5}, w{3.0, 1.0, 5.0};
  std::vector<std::size_t> order;
  EXPECT_EQ(weighted_quantile(h, w, 0.1, order), 0.2);  // 0.9 of 9: the first value (1)
  EXPECT_EQ(weighted_quantile(h, w, 0.5, order), 0.5);  // 4.5: reached at 1 + 5
  EXPECT_EQ(weighted_quantile(h, w, 0.7, order), 1.5);
  EXPECT_TRUE(std::isnan(weighted_quantile({}, {}, 0.5, order)));
}

// ---- Entrainment (entrainment.hpp) ----

// Bins of 1 mm over a 4 mm channel; the lift level 0.1 mm above the top at y = 0, flux
// levels at 0.4 and 1 mm.
EntrainmentOptions entrainment_options() {
  EntrainmentOptions e;
  e.layer_top = 0.0;
  e.lift_height = 1e-4;
  e.heights = {0.4e-3, 1e-3};
  e.bin_width = 1e-3;
  e.x_origin = 0.0;
  e.x_start = 0.0;
  e.x_end = 4e-3;
  return e;
}

struct Moving {
  std::vector<std::int32_t> id{0, 1, 2};
  std::vector<double> x{0.5e-3, 1.5e-3, 2.5e-3}, y{-0.1e-3, -0.1e-3, -0.1e-3};
  std::vector<double> x0{0.5e-3, 1.5e-3, 2.5e-3}, mass{1e-8, 2e-8, 4e-8};
  EntrainmentParcels view() const { return {id, x, y, x0, mass}; }
};

TEST(Entrainment, KnownCrossingsGiveTheRatePerLengthOfLayerWhereTheParcelsStarted) {
  Entrainment e(entrainment_options());
  Moving p;
  EXPECT_FALSE(e.sample(p.view(), 0.0).has_rates);
  // In 10 us parcel 1 rises to 0.5 mm and drifts to x = 3.2 mm: 2e-8 kg/m left the layer's
  // second millimetre (it started at 1.5 mm), and crossed 0.4 mm over the fourth.
  p.y[1] = 0.5e-3;
  p.x[1] = 3.2e-3;
  EntrainmentSample s = e.sample(p.view(), 1e-5);
  ASSERT_TRUE(s.has_rates);
  EXPECT_DOUBLE_EQ(s.lifted_rate, 2e-8 / 1e-5);
  EXPECT_DOUBLE_EQ(s.entrainment[1], 2e-8 / 1e-5 / 1e-3);
  EXPECT_EQ(s.entrainment[3], 0.0);
  EXPECT_DOUBLE_EQ(s.height_rate[0], 2e-8 / 1e-5);
  EXPECT_DOUBLE_EQ(s.height_flux[0][3], 2e-8 / 1e-5 / 1e-3);
  EXPECT_EQ(s.height_rate[1], 0.0);
  EXPECT_EQ(s.height_max[3], 0.5e-3);
  EXPECT_EQ(s.height_p90[3], 0.5e-3);
  EXPECT_TRUE(std::isnan(s.height_max[1]));
  EXPECT_DOUBLE_EQ(s.bin_x[3], 3.5e-3);
  // Then 20 us later it falls back below the lift level while parcel 2 rises to 2 mm: the net
  // lifted rate is (4 - 2) e-8 kg/m over 20 us.
  p.y[1] = 0.05e-3;
  p.y[2] = 2e-3;
  s = e.sample(p.view(), 3e-5);
  EXPECT_DOUBLE_EQ(s.lifted_rate, 2e-8 / 2e-5);
  EXPECT_DOUBLE_EQ(s.entrainment[1], -2e-8 / 2e-5 / 1e-3);
  EXPECT_DOUBLE_EQ(s.entrainment[2], 4e-8 / 2e-5 / 1e-3);
  EXPECT_DOUBLE_EQ(s.height_rate[1], 4e-8 / 2e-5);
}

// The acceptance test: the entrainment rate integrated over time, binned or not, is the
// lifted mass the dust cloud counts, for parcels that rise, drift and fall back at random.
TEST(Entrainment, TheRateIntegratedOverTimeIsTheLiftedMass) {
  const EntrainmentOptions eo = entrainment_options();
  DustCloudOptions co = options();
  co.classes = 1;
  Entrainment e(eo);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> step(-0.3e-3, 0.4e-3), unit(0.0, 1.0);
  const std::size_t n = 200;
  std::vector<std::int32_t> id(n);
  std::vector<double> x(n), y(n, -0.2e-3), x0(n), mass(n), temperature(n, 300.0);
  for (std::size_t i = 0; i < n; ++i) {
    id[i] = static_cast<std::int32_t>(n - 1 - i);  // any order
    x[i] = x0[i] = 4e-3 * unit(random);
    mass[i] = 1e-8 * (1.0 + unit(random));
  }
  const std::vector<double> c(12, 0.0);
  DustCloudScratch scratch;
  double integral = 0.0, binned = 0.0, through = 0.0, t = 0.0;
  DustCloud cloud;
  for (int k = 0; k <= 60; ++k) {
    const EntrainmentSample s = e.sample({id, x, y, x0, mass}, t);
    cloud = dust_cloud({x, y, mass, temperature, {}, {}}, {kXFaces, kYFaces, c}, co, scratch);
    if (k == 0) {
      EXPECT_EQ(cloud.all.lifted_mass, 0.0);  // the layer starts below the lift level
    } else {
      integral += s.lifted_rate * s.interval;
      through += s.height_rate[0] * s.interval;
      for (std::size_t b = 0; b < s.bin_x.size(); ++b)
        binned += s.entrainment[b] * 1e-3 * s.interval;  // bins of 1 mm
    }
    t += 1e-6 * (1.0 + unit(random));  // uneven outputs
    for (std::size_t i = 0; i < n; ++i) {
      y[i] = std::clamp(y[i] + step(random), -0.5e-3, 1.9e-3);
      x[i] = std::clamp(x[i] + 0.2e-3 * unit(random), 0.0, 3.99e-3);
    }
  }
  ASSERT_GT(cloud.all.lifted_mass, 0.0);
  EXPECT_NEAR(integral, cloud.all.lifted_mass, 1e-12 * cloud.all.lifted_mass);
  EXPECT_NEAR(binned, cloud.all.lifted_mass, 1e-12 * cloud.all.lifted_mass);
  // The flux through 0.4 mm integrates to the mass above 0.4 mm.
  EXPECT_NEAR(through, cloud.mass_above[0], 1e-12 * cloud.mass_above[0]);
}

// A restarted run continues the entrainment bit for bit: the parcels' sides of the levels and
// the last time travel in the checkpoint.
TEST(Entrainment, SavedAndRestoredContinuesBitwise) {
  Entrainment a(entrainment_options());
  Moving p;
  (void)a.sample(p.view(), 0.0);
  p.y[1] = 0.5e-3;
  (void)a.sample(p.view(), 1e-5);
  Snapshot snap;
  a.save(snap, "insitu/dust_cloud/");
  Entrainment b(entrainment_options());
  b.restore(snap, "insitu/dust_cloud/");
  p.y[1] = 0.05e-3;
  p.y[2] = 2e-3;
  const EntrainmentSample sa = a.sample(p.view(), 3e-5), sb = b.sample(p.view(), 3e-5);
  EXPECT_EQ(sa.interval, sb.interval);
  EXPECT_EQ(sa.lifted_rate, sb.lifted_rate);
  EXPECT_EQ(sa.entrainment, sb.entrainment);
  EXPECT_EQ(sa.height_flux, sb.height_flux);
  // A fresh tracker (no restore) would see no rates: the state is what carries them.
  Entrainment fresh(entrainment_options());
  EXPECT_FALSE(fresh.sample(p.view(), 3e-5).has_rates);
}

// ---- The scene keys ----

/// The message of the SceneError that parsing the shock-over-dust scene with `overrides` throws (""
/// if none).
std::string refusal(const std::vector<std::string>& overrides) {
  try {
    (void)parse_scene(testing::kShockOverDust, "cloud.toml", overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(DustCloudKeys, BadInputIsRefusedNamingTheKey) {
  std::string m = refusal({"output.explosible_lower=0.5", "output.explosible_upper=0.5"});
  EXPECT_NE(m.find("output.explosible_upper"), std::string::npos) << m;
  EXPECT_NE(m.find("greater than explosible_lower"), std::string::npos) << m;
  m = refusal({"output.explosible_lower=0.5", "output.explosible_upper=0.1"});
  EXPECT_NE(m.find("output.explosible_upper"), std::string::npos) << m;
  for (const char* key : {"explosible_lower", "explosible_upper", "cloud_filter_width",
                          "fines_diameter", "entrainment_bin_width", "cloud_top_concentration"}) {
    m = refusal({std::string("output.") + key + "=-0.01"});
    EXPECT_NE(m.find(std::string("output.") + key), std::string::npos) << key << ": " << m;
  }
  m = refusal({"output.entrainment_heights=[0.001, -0.001]"});
  EXPECT_NE(m.find("output.entrainment_heights"), std::string::npos) << m;
  m = refusal({"output.entrainment_heights=[0.005]"});  // 4 mm of channel above the layer
  EXPECT_NE(m.find("not inside the channel"), std::string::npos) << m;
  // The old keys in g/m^3: refused, naming the new keys and their unit.
  m = refusal({"output.explosible_concentration=50"});
  EXPECT_NE(m.find("output.explosible_concentration"), std::string::npos) << m;
  EXPECT_NE(m.find("explosible_lower"), std::string::npos) << m;
  EXPECT_NE(m.find("kg/m^3"), std::string::npos) << m;
  m = refusal({"output.explosible_concentration=0.04"});  // meant as kg/m^3: refused too
  EXPECT_NE(m.find("explosible_upper"), std::string::npos) << m;
  m = refusal({"output.cloud_edge_concentration=1"});
  EXPECT_NE(m.find("cloud_top_concentration"), std::string::npos) << m;
  EXPECT_EQ(refusal({}), "");
}

TEST(DustCloudKeys, TheDefaultFilterWidthMakesTheQuantumATenthOfTheLowerLimit) {
  // 2,404 parcels of 100 um at 980 kg/m^3 fill a 16 mm x 2 mm layer to alpha_p 0.59: each
  // weighs m = 0.59 A rho / N = 7.7e-6 kg/m (per metre of span). A tenth of 0.05 kg/m^3 needs
  // cells of sqrt(m / 0.005) = 39 mm, more than the 4 mm of channel above the layer, so the
  // default stops there.
  const Scene s = parse_scene(testing::kShockOverDust, "cloud.toml");
  const double m = largest_parcel_mass(s.particles);
  EXPECT_NEAR(m, 0.59 * 16e-3 * 2e-3 * 980.0 / 2404.0, 1e-15 * m);
  // The layer the run makes holds parcels of that mass.
  const ParcelSystem layer = make_layer_system(s.particles);
  EXPECT_NEAR(*std::max_element(layer.mass.begin(), layer.mass.end()), m, 1e-15 * m);
  EXPECT_EQ(s.output.cloud_filter_width, 4e-3);
  EXPECT_FALSE(quantum_resolves(concentration_quantum(m, 4e-3), 0.05));
  EXPECT_EQ(s.output.entrainment_heights, (std::vector<double>{1e-3, 2e-3}));  // 5 mm is outside
  EXPECT_DOUBLE_EQ(s.output.entrainment_bin_width, 0.4e-3);
  EXPECT_EQ(s.output.explosible_lower, 0.05);
  EXPECT_EQ(s.output.explosible_upper, 2.0);
  EXPECT_EQ(s.output.fines_diameter, 75e-6);
  // A lower limit of 10 kg/m^3 needs cells of sqrt(m / 1) = 2.8 mm: the channel allows them.
  const Scene rich = parse_scene(testing::kShockOverDust, "cloud.toml",
                                 {"output.explosible_lower=10.0", "output.explosible_upper=20.0"});
  EXPECT_DOUBLE_EQ(rich.output.cloud_filter_width, std::sqrt(m / 1.0));
  EXPECT_NEAR(concentration_quantum(m, rich.output.cloud_filter_width), 1.0, 1e-12);
  EXPECT_TRUE(quantum_resolves(concentration_quantum(m, rich.output.cloud_filter_width), 10.0));
}

}  // namespace
}  // namespace dustlift
