// The gas on x-slabs over MPI ranks (docs/parallel.md), run by ctest as `mpirun -np 2`:
// every rank runs every test, rank 0 also runs the same scene on one rank and compares bit
// for bit.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "insitu/checkpoint.hpp"
#include "mpi/mpi_test_main.hpp"
#include "solver/core/errors.hpp"
#include "solver/parallel/world.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"

namespace dustlift {
namespace {

// The paper scene's gas (Table 2: Mach 1.44 into air, thermally perfect, Gordon-Wilke
// transport, MUSCL-3 SLAU2, no-slip floor and ceiling, inflow/outflow), on a short channel:
// 180 x 40 cells, stretched upstream and above, so the slab cut (column 90, x = 17.5 mm)
// lies in the uniform part, which the shock crosses after ~400 steps; the rounding noise
// ahead of it (which exact skipping must handle at the cut) reaches the cut much earlier.
// The scene is cases/paper/vertical_shock_gas.toml (the benchmark's) with these overrides.
const std::vector<std::string> kShortChannel = {"grid.x.start=-0.020",      "grid.x.end=0.040",
                                                "grid.x.cells_below=20",    "grid.y.end=0.010",
                                                "grid.y.uniform_end=0.006", "grid.y.cells_above=8"};

// A Riemann problem at rest in a periodic channel, cut at x = 50 mm: the disturbance reaches
// the cut from rank 1's side while rank 0's edge cells still rest (skipped). A change moves
// one cell per stage, so whether it reaches a neighbour's stencil within a step depends on
// the jump's distance from the cut modulo three cells: at 5 cells (52.5 mm) it does, and
// without the exchanged edge updates (SlabHalo::fill) eight of the arrays differ; at 4 or
// 6 cells nothing would. The shock then crosses the periodic join into rank 0. Calorically
// perfect, viscous.
const char* kPeriodic = R"(
[run]
name = "slab_periodic"
end_time = 1.0
[grid.x]
start = 0.0
end = 0.1
cells = 200
[grid.y]
start = 0.0
end = 0.02
cells = 48
[gas]
thermo = "calorically_perfect"
[gas.transport]
model = "sutherland"
[boundary]
left = "periodic"
right = "periodic"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "riemann"
position = 0.0525
left = { rho = 1.6, p = 1.6e5 }
right = { rho = 1.2, p = 1.0e5 }
[output]
interval = 0.0
)";

const Communicator& world() {
  static const std::unique_ptr<Communicator> w = make_world_communicator();
  return *w;
}

Scene scene_of(const char* text, const std::vector<std::string>& overrides = {}) {
  return parse_scene(text, "slab_test.toml", overrides);
}

/// The paper's gas on the short channel, with more overrides.
Scene paper_gas(std::vector<std::string> overrides = {}) {
  overrides.insert(overrides.begin(), kShortChannel.begin(), kShortChannel.end());
  return load_scene(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/paper/vertical_shock_gas.toml",
                    overrides);
}

void advance_steps(Simulation& sim, int steps) {
  for (int k = 0; k < steps; ++k) sim.advance(std::numeric_limits<double>::infinity());
}

/// Number of gas arrays of two snapshots that differ in any bit (rank 0; 0 elsewhere).
int differing_gas_arrays(const Snapshot& a, const Snapshot& b, std::string& names) {
  int n = 0;
  for (const auto& [key, values] : a.f64) {
    if (key.rfind("gas/", 0) != 0 && key.rfind("run/", 0) != 0) continue;
    const auto it = b.f64.find(key);
    bool same = it != b.f64.end() && it->second.size() == values.size();
    for (std::size_t k = 0; same && k < values.size(); ++k) {
      same = std::memcmp(&values[k], &it->second[k], sizeof(double)) == 0;
    }
    if (!same) {
      ++n;
      names += key + " ";
    }
  }
  return n;
}

/// The scene run `steps` steps on one rank with `threads` threads (rank 0 only).
Snapshot one_rank_run(const Scene& scene, int steps, int threads) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Simulation one(scene);
  advance_steps(one, steps);
  omp_set_num_threads(before);
  return one.snapshot();
}

TEST(SlabGas, CutsTheChannelIntoEqualSlabsAndKeepsTheWholeGridsGeometry) {
  Simulation sim(paper_gas(), &world());
  ASSERT_EQ(world().size(), 2) << "run this suite with mpirun -np 2";
  EXPECT_TRUE(sim.decomposed());
  EXPECT_EQ(sim.slab().bounds, (std::vector<int>{0, 90, 180}));
  const Grid2D& slab = sim.grid();
  const Grid2D& whole = sim.whole_grid();
  const int i0 = sim.slab().first_column();
  EXPECT_EQ(slab.nx(), 90);
  for (int i = -slab.ghosts(); i <= slab.nx() + slab.ghosts(); ++i) {
    ASSERT_EQ(slab.x().face(i), whole.x().face(i + i0)) << i;
  }
}

TEST(SlabGas, PaperGasOnTwoRanksMatchesOneRankBitForBit) {
  // Exact skipping, each slab on its own ranges with the edge updates at the cut (the other
  // tests skip within the default tolerance, agreed over the slabs).
  const Scene scene = paper_gas({"run.exact=true"});
  const int steps = 700;  // the shock crosses the cut
  omp_set_num_threads(1);
  Simulation sim(scene, &world());
  advance_steps(sim, steps);
  const Snapshot two = sim.snapshot();
  if (!world().is_root()) return;
  EXPECT_GT(sim.whole_gas()->primitives().p->operator()(140, 5), 1.5e5)
      << "the shock has not crossed the cut";
  // 2 ranks x 1 thread against 1 rank x 2 threads and 1 rank x 1 thread.
  for (int threads : {2, 1}) {
    std::string names;
    EXPECT_EQ(differing_gas_arrays(one_rank_run(scene, steps, threads), two, names), 0)
        << threads << ": " << names;
  }
}

TEST(SlabGas, CutsFollowTheWorkAndTheResultsDoNot) {
  // Cuts recomputed every 20 steps: at first the work is all behind the shock on rank 0, so
  // the cut moves left; as the disturbance spreads it moves back.
  const Scene scene = paper_gas({"run.rebalance_steps=20"});
  omp_set_num_threads(1);
  Simulation sim(scene, &world());
  advance_steps(sim, 20);
  EXPECT_EQ(sim.rebalances(), 1);
  EXPECT_LT(sim.slab().bounds[1], 60) << "the cut did not follow the work";
  EXPECT_EQ(sim.grid().nx(), sim.slab().columns());
  advance_steps(sim, 380);
  EXPECT_GE(sim.rebalances(), 2);
  const Snapshot two = sim.snapshot();
  if (!world().is_root()) return;
  std::string names;
  EXPECT_EQ(differing_gas_arrays(one_rank_run(scene, 400, 1), two, names), 0) << names;
}

TEST(SlabGas, SkippingWithinAToleranceMatchesOneRankWithMovingCutsAndPeriodicEnds) {
  // run.rest_tolerance changes the bits of the noise it skips, so every slab must skip what
  // one grid skips: the rounding noise ahead of the shock crosses the cut long before the
  // shock, and the cuts move (the slab's place in the whole grid changes); in the periodic
  // channel the first slab's left ghosts are the last slab's cells.
  const Scene moving = paper_gas({"run.rebalance_steps=20"});  // within the default 1e-10
  const Scene periodic = scene_of(kPeriodic);                  // within the default 1e-10
  omp_set_num_threads(1);
  Simulation sim(moving, &world());
  advance_steps(sim, 700);
  EXPECT_GE(sim.rebalances(), 2);
  const Snapshot two = sim.snapshot();
  Simulation sim_periodic(periodic, &world());
  advance_steps(sim_periodic, 300);
  const Snapshot two_periodic = sim_periodic.snapshot();
  if (!world().is_root()) return;
  EXPECT_GT(sim.whole_gas()->primitives().p->operator()(140, 5), 1.5e5)
      << "the shock has not crossed the cut";
  for (int threads : {2, 1}) {
    std::string names;
    EXPECT_EQ(differing_gas_arrays(one_rank_run(moving, 700, threads), two, names), 0)
        << threads << ": " << names;
  }
  std::string names;
  EXPECT_EQ(differing_gas_arrays(one_rank_run(periodic, 300, 1), two_periodic, names), 0)
      << "periodic: " << names;
  // The tolerance mattered: exact skipping gives other bits.
  EXPECT_GT(differing_gas_arrays(one_rank_run(paper_gas({"run.exact=true"}), 700, 1), two, names),
            0);
}

TEST(SlabGas, PeriodicChannelOnTwoRanksMatchesOneRank) {
  // Exact skipping: its slabs skip on their own (a jump stands at the periodic join, so one
  // grid, and slabs that agree with it, would skip nothing and the cuts would not move).
  const Scene scene = scene_of(kPeriodic, {"run.exact=true"});
  omp_set_num_threads(1);
  Simulation sim(scene, &world());
  EXPECT_EQ(sim.slab().left(),
            1 - world().rank());  // the join makes each rank the other's neighbour both ways
  advance_steps(sim, 300);
  // Moving cuts in a periodic channel (the state then comes from the whole grid's arrays,
  // ghost columns at the periodic ends included, which must be the one-rank run's): the jump
  // deep in rank 1's slab, so that the work is all there at first.
  const Scene moving_scene =
      scene_of(kPeriodic, {"run.exact=true", "run.rebalance_steps=10", "initial.position=0.08"});
  Simulation moving(moving_scene, &world());
  advance_steps(moving, 300);
  EXPECT_GE(moving.rebalances(), 1);
  const Snapshot two_moving = moving.snapshot();
  const Snapshot two = sim.snapshot();
  if (!world().is_root()) return;
  std::string names;
  const Snapshot one = one_rank_run(scene, 300, 1);
  EXPECT_EQ(differing_gas_arrays(one, two, names), 0) << names;
  EXPECT_EQ(differing_gas_arrays(one_rank_run(moving_scene, 300, 1), two_moving, names), 0)
      << "moving cuts: " << names;
}

TEST(SlabGas, CheckpointsRestartOnAnotherRankCount) {
  const Scene scene = paper_gas();
  omp_set_num_threads(1);
  // Two ranks to step 300, a checkpoint, two ranks on to 600; and one rank from the same
  // checkpoint to 600; and two ranks from a one-rank checkpoint of step 300.
  Simulation sim(scene, &world());
  advance_steps(sim, 300);
  Snapshot at_300 = sim.snapshot();
  advance_steps(sim, 300);
  const Snapshot two = sim.snapshot();
  // Rank 0's checkpoint is the file every rank reads on a restart.
  Snapshot one_at_300;
  if (world().is_root()) {
    Simulation one(scene);
    advance_steps(one, 300);
    one_at_300 = one.snapshot();
    std::string names;
    EXPECT_EQ(differing_gas_arrays(one_at_300, at_300, names), 0) << names;
  }
  // Rank 0 writes the checkpoint files; every rank reads them (as `dustlift run --restart`).
  if (world().is_root()) {
    write_checkpoint("slab_gas_two_ranks_300.h5", at_300);
    write_checkpoint("slab_gas_one_rank_300.h5", one_at_300);
  }
  world().barrier();
  at_300 = read_checkpoint("slab_gas_two_ranks_300.h5");
  one_at_300 = read_checkpoint("slab_gas_one_rank_300.h5");
  Simulation from_two(scene, &world());
  from_two.restore(at_300);
  advance_steps(from_two, 300);
  const Snapshot two_again = from_two.snapshot();
  Simulation from_one(scene, &world());
  from_one.restore(one_at_300);
  advance_steps(from_one, 300);
  const Snapshot two_from_one = from_one.snapshot();
  if (!world().is_root()) return;
  Simulation one(scene);
  one.restore(at_300);
  advance_steps(one, 300);
  std::string names;
  EXPECT_EQ(differing_gas_arrays(one.snapshot(), two, names), 0)
      << "1 rank from a 2-rank checkpoint: " << names;
  EXPECT_EQ(differing_gas_arrays(two_again, two, names), 0)
      << "2 ranks from a 2-rank checkpoint: " << names;
  EXPECT_EQ(differing_gas_arrays(two_from_one, two, names), 0)
      << "2 ranks from a 1-rank checkpoint: " << names;
}

TEST(SlabGas, ABlowUpOnOneRankStopsEveryRankWithTheSameMessage) {
  Simulation sim(paper_gas(), &world());
  advance_steps(sim, 5);
  // A cell of rank 1's slab (column 150 of the whole grid) loses its energy.
  // Every rank makes the same calls (the contract of a decomposed run); rank 1 writes.
  Field2D& energy = sim.gas().conserved(3);
  if (world().rank() == 1) energy(150 - sim.slab().first_column(), 10) = -1.0;
  sim.gas().refresh_primitives();
  std::string message;
  try {
    advance_steps(sim, 1);
  } catch (const NumericalFailure& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("gas cell (i, j) = (150, 10)"), std::string::npos) << message;
  // Every rank has the same text: rank 0 compares its own with rank 1's.
  const std::string from_rank_1 =
      world().first_nonempty(world().rank() == 1 ? message : std::string());
  EXPECT_EQ(from_rank_1, message);
}

}  // namespace
}  // namespace dustlift

int main(int argc, char** argv) {
  return dustlift::run_tests_on_every_rank(argc, argv);
}
