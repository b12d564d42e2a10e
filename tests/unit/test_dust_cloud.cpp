// The dust cloud of known parcels over a known concentration field, every number worked out by
// hand (dust_cloud.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "insitu/dust_cloud.hpp"

namespace dustlift {
namespace {

// Cells 1 mm square: x faces 0..4 mm, y faces -1..2 mm; the layer's top at y = 0.
const std::vector<double> kXFaces{0.0, 1e-3, 2e-3, 3e-3, 4e-3};
const std::vector<double> kYFaces{-1e-3, 0.0, 1e-3, 2e-3};

// Five parcels: 0 rests in the layer, 4 sits 50 um above the top (below the 100 um lift
// height), 1-3 are lifted at 0.5, 1.5 and 0.2 mm.
struct Parcels {
  std::vector<double> x{0.5e-3, 1.5e-3, 2.5e-3, 2.6e-3, 3.5e-3};
  std::vector<double> y{-0.5e-3, 0.5e-3, 1.5e-3, 0.2e-3, 0.05e-3};
  std::vector<double> mass{2.0, 5.0, 3.0, 1.0, 4.0};
  std::vector<double> temperature{300.0, 400.0, 500.0, 350.0, 320.0};
  std::vector<double> size_class{0.0, 0.0, 1.0, 1.0, 1.0};
  CloudParcels view() const { return {x, y, mass, temperature, size_class}; }
};

DustCloudOptions options() {
  DustCloudOptions o;
  o.layer_top = 0.0;
  o.lift_height = 1e-4;
  o.explosible_concentration = 0.05;
  o.edge_concentration = 1e-3;
  o.classes = 2;
  return o;
}

// Row 0 is the layer (ignored), row 1 holds two explosible cells, row 2 a trace at the edge level.
std::vector<double> concentration(double top_row_trace) {
  return {500.0, 500.0, 500.0,         500.0,  //
          0.0,   0.06,  0.2,           5e-4,   //
          0.0,   0.0,   top_row_trace, 0.0};
}

TEST(DustCloud, KnownParcelsGiveTheirMassHeightsAndTemperatures) {
  const Parcels p;
  const std::vector<double> c = concentration(2e-3);
  std::vector<double> scratch;
  const DustCloud cloud = dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch);
  EXPECT_EQ(cloud.all.lifted_mass, 9.0);
  EXPECT_EQ(cloud.all.resting_mass, 6.0);
  // Heights sorted 0.2 (1 kg/m), 0.5 (5), 1.5 mm (3): 4.5 of 9 reached at 0.5 mm, 8.1 at 1.5 mm.
  EXPECT_EQ(cloud.all.height_p50, 0.5e-3);
  EXPECT_EQ(cloud.all.height_p90, 1.5e-3);
  EXPECT_EQ(cloud.all.height_p99, 1.5e-3);
  EXPECT_EQ(cloud.all.temperature_max, 500.0);
  EXPECT_DOUBLE_EQ(cloud.all.temperature_mean, (5.0 * 400.0 + 3.0 * 500.0 + 1.0 * 350.0) / 9.0);
  ASSERT_EQ(cloud.per_class.size(), 2u);
  EXPECT_EQ(cloud.per_class[0].lifted_mass, 5.0);
  EXPECT_EQ(cloud.per_class[0].resting_mass, 2.0);
  EXPECT_EQ(cloud.per_class[0].height_p50, 0.5e-3);
  EXPECT_EQ(cloud.per_class[0].temperature_mean, 400.0);
  EXPECT_EQ(cloud.per_class[1].lifted_mass, 4.0);
  EXPECT_EQ(cloud.per_class[1].resting_mass, 4.0);
  EXPECT_EQ(cloud.per_class[1].height_p50, 1.5e-3);  // 1 of 4 at 0.2 mm, the rest at 1.5 mm
  EXPECT_DOUBLE_EQ(cloud.per_class[1].temperature_mean, (3.0 * 500.0 + 350.0) / 4.0);
  // Lifted mass per column: 5 in column 1, 4 in column 2: the first (most downstream) lifted
  // column is 2, the densest 1.
  EXPECT_EQ(cloud.first_lifted_x, 2.5e-3);
  EXPECT_EQ(cloud.densest_lifted_x, 1.5e-3);
}

TEST(DustCloud, KnownConcentrationGivesTheExplosibleAreaAndTheTop) {
  const Parcels p;
  std::vector<double> scratch;
  const std::vector<double> c = concentration(2e-3);
  const DustCloud cloud = dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch);
  // Cells (1, 1) and (2, 1) reach 0.05 kg/m^3; the layer's row does not count.
  EXPECT_DOUBLE_EQ(cloud.explosible_area, 2e-6);
  EXPECT_EQ(cloud.explosible_x_min, 1e-3);
  EXPECT_EQ(cloud.explosible_x_max, 3e-3);
  EXPECT_EQ(cloud.cloud_top, 2e-3);  // row 2 reaches the edge level: its upper face
  // Below the edge level in row 2 the top falls to row 1's upper face.
  const std::vector<double> thin = concentration(9e-4);
  EXPECT_EQ(dust_cloud(p.view(), {kXFaces, kYFaces, thin}, options(), scratch).cloud_top, 1e-3);
}

TEST(DustCloud, NothingLiftedGivesZeroMassAndNaNHeights) {
  Parcels p;
  p.y = {-0.5e-3, -0.5e-3, -0.5e-3, -0.5e-3, -0.5e-3};
  std::vector<double> c(12, 0.0);
  std::vector<double> scratch;
  const DustCloud cloud = dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch);
  EXPECT_EQ(cloud.all.lifted_mass, 0.0);
  EXPECT_EQ(cloud.all.resting_mass, 15.0);
  EXPECT_TRUE(std::isnan(cloud.all.height_p50));
  EXPECT_TRUE(std::isnan(cloud.all.temperature_mean));
  EXPECT_TRUE(std::isnan(cloud.first_lifted_x));
  EXPECT_EQ(cloud.explosible_area, 0.0);
  EXPECT_TRUE(std::isnan(cloud.explosible_x_min));
  EXPECT_EQ(cloud.cloud_top, 0.0);
}

TEST(DustCloud, AClassOutsideTheLayersClassesIsRefused) {
  Parcels p;
  p.size_class[2] = 2.0;
  std::vector<double> c(12, 0.0), scratch;
  EXPECT_THROW(dust_cloud(p.view(), {kXFaces, kYFaces, c}, options(), scratch),
               std::invalid_argument);
}

TEST(WeightedQuantile, ReachesTheShareAtTheFirstValueThatCompletesIt) {
  const std::vector<double> h{1.5, 0.2, 0.5}, w{3.0, 1.0, 5.0};
  std::vector<std::size_t> order;
  EXPECT_EQ(weighted_quantile(h, w, 0.1, order), 0.2);  // 0.9 of 9: the first value (1)
  EXPECT_EQ(weighted_quantile(h, w, 0.5, order), 0.5);  // 4.5: reached at 1 + 5
  EXPECT_EQ(weighted_quantile(h, w, 0.7, order), 1.5);
  EXPECT_TRUE(std::isnan(weighted_quantile({}, {}, 0.5, order)));
}

}  // namespace
}  // namespace dustlift
