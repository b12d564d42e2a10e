// Skipping what rests is exact on the coupled paper scene (reduced): 120 steps with
// run.skip_at_rest on and off give bitwise the same gas (conserved and primitive fields,
// sources, porosity) and parcels (every built-in column, ids, contact history), on 1 and 2
// threads, while the skipping run computes fewer gas cells and steps fewer parcels.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/coupling/grid_transfer.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/sim/simulation.hpp"

using namespace dustlift;

namespace {

std::string tolerance_override(double tol) {
  char text[64];
  std::snprintf(text, sizeof text, "run.rest_tolerance=%.17g", tol);
  return text;
}

const std::string kPaperScene =
    std::string(DUSTLIFT_SOURCE_DIR) + "/cases/paper/vertical_shock.toml";

/// The paper's cells and physics on a 60 mm layer, the shock starting 1 mm upstream of it.
std::vector<std::string> reduced_paper_overrides(bool skip, double rest_tolerance) {
  return {"grid.x.start=-0.02",
          "grid.x.end=0.06",
          "grid.x.cells_below=20",
          "particles.layer.x_max=0.06",
          "grid.y.end=0.012",
          "grid.y.uniform_end=0.008",
          "grid.y.cells_above=8",
          "initial.position=-0.001",
          std::string("run.skip_at_rest=") + (skip ? "true" : "false"),
          tolerance_override(rest_tolerance)};
}

std::unique_ptr<Simulation> run(bool skip, int threads, int steps, double rest_tolerance = 0.0) {
  omp_set_num_threads(threads);
  auto sim = std::make_unique<Simulation>(
      load_scene(kPaperScene, reduced_paper_overrides(skip, rest_tolerance)));
  for (int s = 0; s < steps; ++s) sim->advance(1.0);
  return sim;
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_bitwise_equal(Simulation& a, Simulation& b, const char* what) {
  for (int k = 0; k < 4; ++k) {
    EXPECT_TRUE(same(a.gas().conserved(k).raw(), b.gas().conserved(k).raw()))
        << what << ": conserved " << k;
    EXPECT_TRUE(same(a.gas().source(k).raw(), b.gas().source(k).raw())) << what << ": source " << k;
  }
  for (int k = 0; k < 5; ++k) {
    EXPECT_TRUE(same(a.gas().primitive_field(k).raw(), b.gas().primitive_field(k).raw()))
        << what << ": primitive " << k;
  }
  EXPECT_TRUE(same(a.gas().porosity().raw(), b.gas().porosity().raw())) << what << ": porosity";
  const ParcelSystem& p = *a.parcels();
  const ParcelSystem& q = *b.parcels();
  ASSERT_EQ(p.size(), q.size());
  p.for_each_column_pair(q, [&](const ParcelColumnSpec& c, const auto& mine, const auto& theirs) {
    if constexpr (std::is_same_v<std::decay_t<decltype(mine)>, std::vector<double>>) {
      if (ParcelTable::is_state(c)) {
        EXPECT_TRUE(same(mine, theirs)) << what << ": parcel column " << c.name;
      }
    }
  });
  EXPECT_EQ(p.id, q.id) << what;
  EXPECT_TRUE(same(p.nbr_delta, q.nbr_delta)) << what << ": contact history";
  EXPECT_EQ(p.nbr_index, q.nbr_index) << what;
}

/// The coupling deposits only into the columns that the stepped parcels reach (columns beyond
/// keep their sums). Its alpha_p must be, to the last bit, a deposit of every parcel from
/// scratch in parcel order (eq. 12 over grid_transfer's stencils).
void expect_alpha_p_is_a_full_deposit(const Simulation& sim, const char* what) {
  const Grid2D& g = sim.grid();
  const ParcelSystem& p = *sim.parcels();
  const double volume =
      std::numbers::pi / 6.0 * std::pow(sim.scene().particles.particle_diameter, 3);
  Field2D full(g);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const DepositStencil d =
        deposit_stencil(g, p.x[k], p.y[k], sim.scene().coupling.influence_width);
    for (int m = 0; m < d.count; ++m) {
      const auto mm = static_cast<std::size_t>(m);
      full(d.i[mm], d.j[mm]) += d.fraction[mm] * (p.n_real[k] * volume) / g.area(d.i[mm], d.j[mm]);
    }
  }
  const Field2D& alpha = sim.coupling()->alpha_p();
  int differ = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const double mine = alpha(i, j), fresh = full(i, j);
      differ += std::memcmp(&mine, &fresh, sizeof(double)) != 0;
    }
  EXPECT_EQ(differ, 0) << what << ": cells whose alpha_p is not the full deposit's";
}

}  // namespace

TEST(SkipAtRest, ReducedPaperSceneIsBitwiseTheSameWithSkippingOnAndOff) {
  constexpr int kSteps = 120;
  auto on = run(true, 2, kSteps);
  auto off = run(false, 2, kSteps);
  auto on_one_thread = run(true, 1, kSteps);
  omp_set_num_threads(2);
  ASSERT_GE(on->parcels()->size(), 4096u);
  expect_bitwise_equal(*on, *off, "skip on vs off");
  expect_bitwise_equal(*on, *on_one_thread, "skip on, 2 vs 1 threads");
  expect_alpha_p_is_a_full_deposit(*on, "exact skipping");
  const double gas_share = static_cast<double>(on->gas().cell_updates()) /
                           static_cast<double>(off->gas().cell_updates());
  const double parcel_share = static_cast<double>(on->parcels()->parcel_substeps()) /
                              static_cast<double>(off->parcels()->parcel_substeps());
  std::printf(
      "skipping computed %.3f of the gas cell-stages and stepped %.3f of the parcel-sub-steps\n",
      gas_share, parcel_share);
  EXPECT_LT(gas_share, 0.9);
  EXPECT_LT(parcel_share, 0.9);
  // The shock has moved and parcels have moved: the comparison is not of two resting states.
  double vmax = 0.0;
  for (double v : on->parcels()->vx) vmax = std::max(vmax, std::abs(v));
  EXPECT_GT(vmax, 0.1);
}

// run.rest_tolerance: the rounding noise that runs ahead of the shock is skipped too. Fewer
// cells and parcels are computed than with exact skipping, the run is still the same on 1 and
// 2 threads, and it departs from the exact one only at the level of that noise.
TEST(SkipAtRest, ToleranceSkipsTheNoiseAheadOfTheShockAndChangesOnlyNoise) {
  constexpr int kSteps = 120;
  constexpr double kTolerance = 1e-10;
  auto exact = run(true, 2, kSteps);
  auto tolerant = run(true, 2, kSteps, kTolerance);
  auto tolerant_one_thread = run(true, 1, kSteps, kTolerance);
  omp_set_num_threads(2);
  expect_bitwise_equal(*tolerant, *tolerant_one_thread, "tolerant skipping, 2 vs 1 threads");
  expect_alpha_p_is_a_full_deposit(*tolerant, "tolerant skipping");
  {
    // A restart halfway continues bitwise: the rest counts, the reference they count against
    // and the samples of resting parcels are in the checkpoint.
    auto first_half = run(true, 2, kSteps / 2, kTolerance);
    Simulation restarted(load_scene(kPaperScene, reduced_paper_overrides(true, kTolerance)));
    restarted.restore(first_half->snapshot());
    for (int s = kSteps / 2; s < kSteps; ++s) restarted.advance(1.0);
    expect_bitwise_equal(*tolerant, restarted, "tolerant skipping, restarted halfway");
  }
  const auto effects = tolerant->enabled_effects();
  const bool listed = std::any_of(effects.begin(), effects.end(), [](const std::string& e) {
    return e.find("skipping at rest: within a relative 1e-10") != std::string::npos;
  });
  EXPECT_TRUE(listed) << "dustlift info names the tolerance";
  const double gas_share = static_cast<double>(tolerant->gas().cell_updates()) /
                           static_cast<double>(exact->gas().cell_updates());
  const double parcel_share = static_cast<double>(tolerant->parcels()->parcel_substeps()) /
                              static_cast<double>(exact->parcels()->parcel_substeps());
  std::printf(
      "tolerant skipping computed %.3f of exact skipping's gas cell-stages and stepped %.3f of its "
      "parcel-sub-steps\n",
      gas_share, parcel_share);
  EXPECT_LT(gas_share, 0.8);
  EXPECT_LT(parcel_share, 0.5);
  // Same gas to within 1e-8 of each field's largest value everywhere (a shock moved by a
  // cell would differ by O(1)), same parcels to within 1e-12 m and 1e-8 of the fastest speed.
  for (int k = 0; k < 5; ++k) {
    const auto& a = tolerant->gas().primitive_field(k).raw();
    const auto& b = exact->gas().primitive_field(k).raw();
    double scale = 0.0, diff = 0.0;
    for (std::size_t c = 0; c < a.size(); ++c) {
      scale = std::max(scale, std::abs(b[c]));
      diff = std::max(diff, std::abs(a[c] - b[c]));
    }
    std::printf("primitive %d: max difference %.3g of %.3g\n", k, diff, scale);
    EXPECT_LT(diff, 1e-8 * scale) << "primitive " << k;
  }
  const ParcelSystem& p = *tolerant->parcels();
  const ParcelSystem& q = *exact->parcels();
  ASSERT_EQ(p.size(), q.size());
  double dx = 0.0, dv = 0.0, vmax = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    // Both sorted by cell; compare by id.
    ASSERT_EQ(p.id[i], q.id[i]);
    dx = std::max({dx, std::abs(p.x[i] - q.x[i]), std::abs(p.y[i] - q.y[i])});
    dv = std::max({dv, std::abs(p.vx[i] - q.vx[i]), std::abs(p.vy[i] - q.vy[i])});
    vmax = std::max(vmax, std::abs(q.vx[i]));
  }
  std::printf(
      "parcels: max position difference %.3g m, max velocity difference %.3g m/s (max speed %.3g "
      "m/s)\n",
      dx, dv, vmax);
  EXPECT_GT(vmax, 0.1);
  EXPECT_LT(dx, 1e-12);
  EXPECT_LT(dv, 1e-8 * vmax);
}
