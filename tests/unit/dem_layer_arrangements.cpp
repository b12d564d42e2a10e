// Layer arrangements (docs/dem.md, "Layer structures"): counts, rows and columns, no
// overlap, touching rows of the columnar layer, volume fraction, settling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/scene/scene.hpp"

using namespace dustlift;

namespace {

constexpr double kD = 100e-6;  // parcel diameter of the paper

LayerConfig paper_layer(LayerArrangement a) {
  LayerConfig c;  // 400 mm x 2 mm at 0.59, floor at -2 mm, top at 0
  c.arrangement = a;
  return c;
}

/// Smallest centre distance over all pairs, by bucketing into cells of side `cell` >= that distance.
double min_distance(const std::vector<double>& x, const std::vector<double>& y, double cell) {
  std::map<std::pair<long, long>, std::vector<std::size_t>> bucket;
  auto key = [&](std::size_t i) { return std::pair<long, long>(std::lround(std::floor(x[i] / cell)), std::lround(std::floor(y[i] / cell))); };
  for (std::size_t i = 0; i < x.size(); ++i) bucket[key(i)].push_back(i);
  double best = 1e300;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto [cx, cy] = key(i);
    for (long b = cy - 1; b <= cy + 1; ++b)
      for (long a = cx - 1; a <= cx + 1; ++a) {
        const auto it = bucket.find({a, b});
        if (it == bucket.end()) continue;
        for (std::size_t j : it->second)
          if (j != i) best = std::min(best, std::hypot(x[i] - x[j], y[i] - y[j]));
      }
  }
  return best;
}

/// Areal fraction of the parcels of `pos` in the layer rectangle of `c`.
double fraction_of(const LayerPositions& pos, const LayerConfig& c) {
  return areal_fraction(static_cast<double>(pos.x.size()), kD, (c.x_max - c.x_min) * (c.y_max - c.y_min));
}

}  // namespace

TEST(DemLayerArrangements, ColumnarPaperLayerHasTwentyTouchingRowsOnTheFloor) {
  const LayerConfig c = paper_layer(LayerArrangement::Columnar);
  const LayerPositions L = generate_layer(c, kD);
  EXPECT_EQ(L.lattice.rows, 20);
  EXPECT_EQ(L.lattice.cols, 3005);  // round(60,097 / 20)
  ASSERT_EQ(L.x.size(), 60100u);
  EXPECT_NEAR(L.lattice.pitch_x, 0.4 / 3005, 1e-15);
  // Areal fraction within 1 / (2 cols) relative of the target (the column count is rounded).
  EXPECT_NEAR(fraction_of(L, c) / 0.59, 1.0, 0.5 / 3005);
  // Row-major from the bottom: parcel r * cols + c is row r of column c.
  double worst_gap = 0.0;
  for (int r = 0; r < 20; ++r) {
    for (int k = 0; k < 3005; k += 1) {
      const std::size_t i = static_cast<std::size_t>(r) * 3005 + k;
      ASSERT_EQ(L.x[i], L.x[k]) << "columns are vertical";
      if (r == 0) {
        ASSERT_GE(L.y[i] - c.y_min, 0.5 * kD) << "bottom row must not overlap the floor";
        worst_gap = std::max(worst_gap, L.y[i] - c.y_min - 0.5 * kD);
      } else {
        const double dy = L.y[i] - L.y[i - 3005];
        ASSERT_GE(dy, kD) << "rows must not overlap by round-off";
        worst_gap = std::max(worst_gap, dy - kD);
      }
    }
  }
  EXPECT_LT(worst_gap, 1e-18) << "touching means zero gap up to round-off";
  EXPECT_NEAR(L.y.back() + 0.5 * kD, c.y_max, 1e-15) << "the top row's top is the layer top";
  EXPECT_GE(min_distance(L.x, L.y, 150e-6), kD);
  std::printf("columnar: %d rows x %d columns, pitch %.3f um, areal fraction %.5f, largest gap %.2e m\n",
              L.lattice.rows, L.lattice.cols, L.lattice.pitch_x * 1e6, fraction_of(L, c), worst_gap);
}

TEST(DemLayerArrangements, ColumnarLayerWhoseDepthIsNotAMultipleOfTheDiameterStopsBelowTheTop) {
  LayerConfig c{0.0, 0.01, 0.0, 0.00105, 0.5, 1, LayerArrangement::Columnar, false};
  const LayerPositions L = generate_layer(c, kD);
  EXPECT_EQ(L.lattice.rows, 10);
  EXPECT_NEAR(*std::max_element(L.y.begin(), L.y.end()) + 0.5 * kD, 0.001, 1e-15);
  c.volume_fraction = 0.8;  // columns would have to overlap: at most pi/4 * 10 D / depth = 0.748
  EXPECT_THROW(plan_columnar_layer(c, kD), std::invalid_argument);
}

TEST(DemLayerArrangements, HexagonalPaperLayerHasOffsetRowsWithoutContact) {
  const LayerConfig c = paper_layer(LayerArrangement::Hexagonal);
  const LayerPositions L = generate_layer(c, kD);
  const LayerLattice& P = L.lattice;
  EXPECT_EQ(P.rows, 19);
  EXPECT_EQ(P.cols, 3163);
  ASSERT_EQ(static_cast<std::int64_t>(L.x.size()), P.n_parcels);
  EXPECT_EQ(P.n_parcels, 10 * 3163 + 9 * 3162);
  EXPECT_NEAR(P.pitch_y, 0.002 / 19, 1e-15);
  // The second row starts half a pitch right of the first.
  EXPECT_NEAR(L.x[3163] - L.x[0], 0.5 * P.pitch_x, 1e-15);
  EXPECT_NEAR(L.y[3163] - L.y[0], P.pitch_y, 1e-15);
  const double nearest = min_distance(L.x, L.y, 150e-6);
  EXPECT_NEAR(nearest, std::hypot(0.5 * P.pitch_x, P.pitch_y), 1e-12);
  EXPECT_NEAR(nearest, plan_nearest_distance(c, P), 1e-12);
  EXPECT_GT(nearest, 1.2 * kD);
  EXPECT_NEAR(fraction_of(L, c) / 0.59, 1.0, 0.5 * P.rows / static_cast<double>(P.n_parcels));
  std::printf("hexagonal: %d rows x %d/%d columns, pitch %.3f x %.3f um, nearest %.3f um, %zu parcels, fraction %.5f\n",
              P.rows, P.cols, P.cols - 1, P.pitch_x * 1e6, P.pitch_y * 1e6, nearest * 1e6, L.x.size(), fraction_of(L, c));
}

TEST(DemLayerArrangements, LatticeWithoutJitterSitsOnTheSiteCentres) {
  const LayerConfig c = paper_layer(LayerArrangement::Lattice);
  const LayerPositions L = generate_layer(c, kD);
  EXPECT_EQ(L.lattice.rows, 17);
  EXPECT_EQ(L.lattice.cols, 3536);
  for (std::size_t i = 0; i < L.x.size(); i += 97) {
    const double sx = (L.x[i] - c.x_min) / L.lattice.pitch_x - 0.5, sy = (L.y[i] - c.y_min) / L.lattice.pitch_y - 0.5;
    ASSERT_NEAR(sx, std::round(sx), 1e-9);
    ASSERT_NEAR(sy, std::round(sy), 1e-9);
  }
  EXPECT_NEAR(min_distance(L.x, L.y, 150e-6), std::min(L.lattice.pitch_x, L.lattice.pitch_y), 1e-12);
}

TEST(DemLayerArrangements, EveryArrangementStartsWithoutContactAndAtRest) {
  // 60 mm of the paper layer with the paper's constants: one DEM step moves nothing (no
  // force acts, no pair overlaps; the columnar rows touch at exactly zero overlap).
  for (auto a : {LayerArrangement::JitteredLattice, LayerArrangement::Lattice, LayerArrangement::Columnar,
                 LayerArrangement::Hexagonal}) {
    DemConfig cfg;
    cfg.enabled = true;
    cfg.layer = paper_layer(a);
    cfg.layer.x_max = 0.06;
    cfg.domain = DemDomain{0.0, 0.06, -0.002, 0.02, true, false, true, true, false};
    ParcelSystem s = make_layer_system(cfg);
    const auto y0 = s.y;
    s.step(s.stable_time_step());
    EXPECT_EQ(s.contact_pair_count(), 0u) << layer_arrangement_name(a);
    EXPECT_EQ(s.kinetic_energy(), 0.0) << layer_arrangement_name(a);
  }
}

TEST(DemLayerArrangements, ThreeDimensionalFractionEqualsTheTargetForEveryGeneratedArrangement) {
  // The parser derives real particles per parcel from the parcel count of the plan, so the
  // 3-D solid fraction is the scene's whatever rounding the arrangement needs.
  const std::string base = R"([run]
end_time = 1e-4
[grid]
x = { start = 0.0, end = 0.02, cells = 80 }
y = { start = -0.002, end = 0.01, cells = 48 }
[initial]
kind = "uniform"
state = { p = 101325.0, T = 300.0 }
[particles]
diameter = 100e-6
density = 980.0
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
x_min = 0.0
x_max = 0.02
volume_fraction = 0.59
)";
  for (const char* name : {"jittered_lattice", "lattice", "columnar", "hexagonal"}) {
    const Scene s = parse_scene(base + "arrangement = \"" + name + "\"\n", "layer.toml");
    const LayerLattice plan = plan_layer(s.particles.layer, kD);
    const double alpha = volume_fraction_3d(static_cast<double>(plan.n_parcels), s.particles.real_per_parcel, kD,
                                            0.02 * 0.002);
    EXPECT_NEAR(alpha, 0.59, 1e-12) << name;
    EXPECT_NE(s.resolved_toml.find(std::string("arrangement = '") + name + "'"), std::string::npos) << name;
  }
}

TEST(DemLayerArrangements, SettledBedIsLowerDenserInContactAndAtRest) {
  // 1 mm grains (a 31x larger DEM step than 100 um ones) in a 20 mm x 6 mm box: the jittered
  // lattice at 0.59 falls under gravity until quiet, then the velocities are zeroed.
  DemConfig cfg;
  cfg.enabled = true;
  cfg.particle_diameter = cfg.parcel_diameter = 1e-3;
  cfg.layer = LayerConfig{0.0, 0.02, 0.0, 0.006, 0.59, 3, LayerArrangement::Settled, false};
  cfg.domain = DemDomain{0.0, 0.02, 0.0, 0.05, true, false, true, true, false};
  // e_n = 0.5 (h = 0.05 N s/m for 1 mm grains): the bed comes to rest in fewer steps.
  cfg.contact.damping = cfg.wall_contact.damping = 0.05;
  const LayerPositions start = generate_layer(cfg.layer, 1e-3);
  const ParcelSystem s = make_layer_system(cfg);
  ASSERT_EQ(s.size(), start.x.size());
  double top = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) top = std::max(top, s.y[i] + s.radius[i]);
  const double start_top = *std::max_element(start.y.begin(), start.y.end()) + 0.5e-3;
  const double bed_fraction = areal_fraction(static_cast<double>(s.size()), 1e-3, 0.02 * top);
  EXPECT_EQ(s.kinetic_energy(), 0.0);
  EXPECT_GT(s.contact_pair_count(), s.size() / 2) << "a settled bed rests on contacts";
  EXPECT_LT(top, start_top - 0.2e-3) << "the bed compacts";
  EXPECT_GT(bed_fraction, 0.62);
  EXPECT_EQ(s.y_initial, s.y) << "the run starts from the settled bed";
  std::printf("settled: %zu grains of 1 mm, top %.3f mm (lattice %.3f mm, rectangle 6 mm), bed fraction %.4f, %zu contacts\n",
              s.size(), top * 1e3, start_top * 1e3, bed_fraction, s.contact_pair_count());
}

TEST(DemLayerArrangements, LooseTopKeepsEveryOtherColumnOfTheTopRowsOfTheColumnarLayer) {
  // The paper layer with its top two rows half filled (docs/dem.md, "A looser top"):
  // 1,503 of 3,005 sites in each (the first, third, ...), the 18 rows below untouched.
  const LayerConfig full = paper_layer(LayerArrangement::Columnar);
  LayerConfig loose = full;
  loose.loose_top_rows = 2;
  loose.loose_top_fill = 0.5;
  const LayerPositions F = generate_layer(full, kD), L = generate_layer(loose, kD);
  EXPECT_EQ(L.lattice.n_parcels, F.lattice.n_parcels) << "the plan, and real_per_parcel, stay";
  ASSERT_EQ(L.x.size(), 60100u - 2u * 1502u);
  const std::size_t below = 18u * 3005u;
  for (std::size_t i = 0; i < below; ++i) {
    ASSERT_EQ(L.x[i], F.x[i]);
    ASSERT_EQ(L.y[i], F.y[i]);
  }
  for (int row = 0; row < 2; ++row) {
    for (std::size_t k = 0; k < 1503; ++k) {
      const std::size_t i = below + static_cast<std::size_t>(row) * 1503 + k;
      ASSERT_EQ(L.x[i], F.x[below + static_cast<std::size_t>(row) * 3005 + 2 * k])
          << "row " << 18 + row << " site " << k;
      ASSERT_EQ(L.y[i], F.y[below + static_cast<std::size_t>(row) * 3005]);
    }
  }
  // The loose rows hold half the areal fraction: the rectangle's is 0.59 (18 + 2 * 1503 / 3005)
  // / 20.
  EXPECT_NEAR(fraction_of(L, loose), fraction_of(F, full) * (18.0 + 2.0 * 1503.0 / 3005.0) / 20.0,
              1e-12);
}

TEST(DemLayerArrangements, LooseTopThinsOnlyTheTopRowsOfEveryArrangement) {
  // fill 1/3 of the top three rows: ceil(n / 3) sites of each row's n, evenly spread; the
  // parcels below are those of the full layer, bit for bit (the jittered lattice draws its
  // jitter for the left-out sites too).
  for (LayerArrangement a : {LayerArrangement::Lattice, LayerArrangement::JitteredLattice,
                             LayerArrangement::Columnar, LayerArrangement::Hexagonal}) {
    LayerConfig full = paper_layer(a);
    full.x_max = 0.06;
    LayerConfig loose = full;
    loose.loose_top_rows = 3;
    loose.loose_top_fill = 1.0 / 3.0;
    const LayerPositions F = generate_layer(full, kD), L = generate_layer(loose, kD);
    const int rows = F.lattice.rows;
    // Row boundaries: the full layer's rows are the runs of equal site y (no jitter) or of
    // site index; count by position instead, as the top 3 rows start at the (rows - 3)-th.
    const double pitch_y = F.lattice.pitch_y;
    const double cut =
        full.y_min + (rows - 3) * pitch_y - 0.01 * kD;  // below row rows-3's lowest jitter
    std::size_t below_full = 0, below_loose = 0;
    for (double y : F.y) below_full += y < cut ? 1u : 0u;
    for (double y : L.y) below_loose += y < cut ? 1u : 0u;
    ASSERT_EQ(below_loose, below_full) << layer_arrangement_name(a);
    for (std::size_t i = 0; i < below_full; ++i) {
      ASSERT_EQ(L.x[i], F.x[i]) << layer_arrangement_name(a);
      ASSERT_EQ(L.y[i], F.y[i]) << layer_arrangement_name(a);
    }
    // Each of the top three rows of the full layer has n sites (lattice: minus the seeded
    // empty ones); the loose layer keeps a third of them, to within one per row.
    const double kept = static_cast<double>(L.x.size() - below_loose),
                 had = static_cast<double>(F.x.size() - below_full);
    EXPECT_NEAR(kept, had / 3.0, 3.0) << layer_arrangement_name(a);
    EXPECT_GT(kept, 0.0);
  }
}
