// The coupled CFD-DEM step on x-slabs over MPI ranks, run by ctest as
// `mpirun -np 2`: the shock runs over a dust layer cut between the ranks; rank 0 gathers the
// gas and the parcels and compares them bit for bit with the same scene on one rank.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "insitu/checkpoint.hpp"
#include "mpi/mpi_test_main.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/parallel/world.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/simulation.hpp"

namespace dustlift {
namespace {

const Communicator& world() {
  static const std::unique_ptr<Communicator> w = make_world_communicator();
  return *w;
}

// The quickstart (the paper's physics: Mach 1.44, thermally perfect air, Gordon-Wilke,
// drag, Magnus, pressure force, torque, heat, two-way) on a 30 mm channel over a 15 mm layer
// (about 2,200 parcels); the cut (column 25 of 50, x = 7.5 mm) lies inside the layer, and
// the shock crosses it after about 90 steps.
Scene reduced_quickstart(std::vector<std::string> more = {}) {
  std::vector<std::string> overrides = {"grid.x.start=-0.010",        "grid.x.end=0.020",
                                        "grid.x.cells_below=10",      "grid.y.end=0.008",
                                        "grid.y.uniform_end=0.006",   "grid.y.cells_above=4",
                                        "particles.layer.x_max=0.015"};
  overrides.insert(overrides.end(), more.begin(), more.end());
  return load_scene(std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml", overrides);
}

void advance_steps(Simulation& sim, int steps) {
  for (int k = 0; k < steps; ++k) sim.advance(std::numeric_limits<double>::infinity());
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Differences between the decomposed run (gathered on rank 0) and a one-rank run of the
/// same scene with `threads` threads: the gas arrays of the snapshots, every parcel column
/// (attached ones too), the parcel order and the contact history. Rank 0's count; 0 elsewhere.
int differences(const Scene& scene, int steps, Simulation& two, int threads, std::string& names) {
  const Snapshot gas_two = two.snapshot();  // its gas is the gathered whole grid
  std::vector<double> mine;
  two.parcels()->pack_owned(mine);
  std::vector<std::vector<double>> pieces;
  world().gather(mine, pieces);
  if (!world().is_root()) return 0;
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Simulation one(scene);
  advance_steps(one, steps);
  omp_set_num_threads(before);
  int n = 0;
  auto check = [&](bool same, const std::string& what) {
    if (!same) {
      ++n;
      names += what + " ";
    }
  };
  const Snapshot gas_one = one.snapshot();
  for (const auto& [key, values] : gas_one.f64) {
    if (key.rfind("gas/", 0) != 0) continue;
    const auto it = gas_two.f64.find(key);
    check(it != gas_two.f64.end() && same_bits(values, it->second), key);
  }
  const ParcelSystem& serial = *one.parcels();
  ParcelSystem gathered(scene.particles);
  for (std::size_t k = 0; k < serial.attached_count(); ++k)
    gathered.attach_column(serial.attached_spec(k));
  gathered.assign_packed(pieces);
  check(gathered.size() == serial.size(), "parcel count");
  if (gathered.size() != serial.size()) return n;
  gathered.for_each_column_pair(
      serial, [&](const ParcelColumnSpec& c, const auto& mine, const auto& theirs) {
        if (ParcelTable::is_state(c)) check(same_bits(mine, theirs), "parcels/" + c.name);
      });
  for (std::size_t c = 0; c < serial.attached_count(); ++c) {
    check(same_bits(gathered.attached(c), serial.attached(c)),
          "parcels/" + serial.attached_spec(c).name);
  }
  check(same_bits(gathered.id, serial.id), "parcels/id (order)");
  check(same_bits(gathered.nbr_index, serial.nbr_index), "parcels/nbr_index");
  check(same_bits(gathered.nbr_delta, serial.nbr_delta), "parcels/nbr_delta");
  check(same_bits(gathered.wall_delta, serial.wall_delta), "parcels/wall_delta");
  return n;
}

TEST(SlabCoupled, ShockOverDustOnTwoRanksMatchesOneRankBitForBit) {
  ASSERT_EQ(world().size(), 2) << "run under mpirun -np 2";
  const Scene scene = reduced_quickstart();
  constexpr int kSteps = 150;
  omp_set_num_threads(1);
  Simulation two(scene, &world());
  ASSERT_TRUE(two.decomposed());
  // Early on the parcels ahead of the shock rest exactly and are skipped on the slabs too
  // (exactly: the comparison below), on the rank that holds them.
  constexpr int kEarly = 5;
  advance_steps(two, kEarly);
  const double skipped =
      static_cast<double>(two.parcels()->size() - two.coupling()->last_active_parcels());
  EXPECT_GT(-world().min(-skipped), 100.0);
  advance_steps(two, kSteps - kEarly);
  EXPECT_GT(two.parcels()->size(), two.parcels()->owned_count());  // rank copies
  // The parcels at the cut (within 1 mm of it) have moved.
  const ParcelSystem& p = *two.parcels();
  double moved = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.is_rank_copy(i) && std::abs(p.x_initial[i] - 0.0075) < 1e-3) {
      moved = std::max(moved, std::hypot(p.x[i] - p.x_initial[i], p.y[i] - p.y_initial[i]));
    }
  }
  moved = -world().min(-moved);
  EXPECT_GT(moved, 1e-7);
  for (int threads : {1, 2}) {
    if (threads == 2 && world().is_root()) {
      // The shock is past the cut (the whole gas, gathered by the snapshot): column 34 of
      // the whole grid is x = 11.75 mm, 4.25 mm beyond it, just above the layer.
      EXPECT_GT((*two.whole_gas()->primitives().p)(34, 6), 1.5e5)
          << "the shock has not crossed the cut";
    }
    std::string names;
    EXPECT_EQ(differences(scene, kSteps, two, threads, names), 0)
        << threads << " thread(s): " << names;
  }
}

TEST(SlabCoupled, PolydisperseLayerOnTwoRanksMatchesOneRankBitForBit) {
  ASSERT_EQ(world().size(), 2) << "run under mpirun -np 2";
  // The reduced quickstart with three log-normal classes in its 100 um parcels (its
  // particles.diameter line dropped: a distribution derives it).
  const std::string path = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";
  std::string text = read_input_file(path, "scene");
  const std::size_t at = text.find("diameter = 100e-6");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find('\n', at) - at);
  const Scene scene = parse_scene(
      text, path,
      {"grid.x.start=-0.010", "grid.x.end=0.020", "grid.x.cells_below=10", "grid.y.end=0.008",
       "grid.y.uniform_end=0.006", "grid.y.cells_above=4", "particles.layer.x_max=0.015",
       "particles.parcel_diameter=100e-6", "particles.size_distribution.median=70e-6",
       "particles.size_distribution.geometric_std=1.3", "particles.size_distribution.classes=3"});
  ASSERT_EQ(scene.particles.size_classes.size(), 3u);
  constexpr int kSteps = 120;
  omp_set_num_threads(1);
  Simulation two(scene, &world());
  ASSERT_TRUE(two.decomposed());
  advance_steps(two, kSteps);
  EXPECT_GT(two.parcels()->size(), two.parcels()->owned_count());  // rank copies
  // Parcels of every class have moved (the comparison below is not of a layer at rest).
  const ParcelSystem& p = *two.parcels();
  double moved[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto c = static_cast<std::size_t>(p.size_class[i]);
    moved[c] = std::max(moved[c], std::hypot(p.x[i] - p.x_initial[i], p.y[i] - p.y_initial[i]));
  }
  for (double& m : moved) m = -world().min(-m);
  for (double m : moved) EXPECT_GT(m, 1e-7);
  for (int threads : {1, 2}) {
    std::string names;
    EXPECT_EQ(differences(scene, kSteps, two, threads, names), 0)
        << threads << " thread(s): " << names;
  }
}

TEST(SlabCoupled, ClassParcelsRestitutionAndCohesionOnTwoRanksMatchOneRankBitForBit) {
  ASSERT_EQ(world().size(), 2) << "run under mpirun -np 2";
  // The reduced quickstart with three log-normal classes in parcels of their own sizes
  // (parcel_ratio), the restitution per pair and van der Waals cohesion with a tail across
  // gaps (its reach widens the rank copies).
  const std::string path = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml";
  std::string text = read_input_file(path, "scene");
  for (const char* line : {"diameter = 100e-6", "damping = 1.0e-4"}) {
    const std::size_t at = text.find(line);
    ASSERT_NE(at, std::string::npos) << line;
    text.erase(at, text.find('\n', at) - at);
  }
  const Scene scene = parse_scene(
      text, path,
      {"grid.x.start=-0.010", "grid.x.end=0.020", "grid.x.cells_below=10", "grid.y.end=0.008",
       "grid.y.uniform_end=0.006", "grid.y.cells_above=4", "particles.layer.x_max=0.015",
       "particles.size_distribution.median=70e-6", "particles.size_distribution.geometric_std=1.3",
       "particles.size_distribution.classes=3", "particles.parcel_ratio=[2, 1.5, 1.2]",
       "particles.contact.restitution=0.9", "particles.cohesion.hamaker=1e-19",
       "particles.cohesion.cutoff=2e-6"});
  ASSERT_TRUE(has_class_parcels(scene.particles.size_classes));
  constexpr int kSteps = 120;
  omp_set_num_threads(1);
  Simulation two(scene, &world());
  ASSERT_TRUE(two.decomposed());
  advance_steps(two, kSteps);
  EXPECT_GT(two.parcels()->size(), two.parcels()->owned_count());  // rank copies
  const ParcelSystem& p = *two.parcels();
  double moved[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto c = static_cast<std::size_t>(p.size_class[i]);
    moved[c] = std::max(moved[c], std::hypot(p.x[i] - p.x_initial[i], p.y[i] - p.y_initial[i]));
  }
  for (double& m : moved) m = -world().min(-m);
  for (double m : moved) EXPECT_GT(m, 1e-7);
  for (int threads : {1, 2}) {
    std::string names;
    EXPECT_EQ(differences(scene, kSteps, two, threads, names), 0)
        << threads << " thread(s): " << names;
  }
}

/// The arrays (of every type) of two snapshots that differ in any bit or exist in one only.
template <class Map>
void differing_arrays(const Map& a, const Map& b, std::string& names) {
  for (const auto& [key, values] : a) {
    const auto it = b.find(key);
    if (it == b.end() || !same_bits(values, it->second)) names += key + " ";
  }
  for (const auto& [key, values] : b) {
    if (a.find(key) == a.end()) names += key + " ";
  }
}
std::string differing_datasets(const Snapshot& a, const Snapshot& b) {
  std::string names;
  differing_arrays(a.f64, b.f64, names);
  differing_arrays(a.i64, b.i64, names);
  differing_arrays(a.i32, b.i32, names);
  differing_arrays(a.i8, b.i8, names);
  return names;
}

TEST(SlabCoupled, SkippingWithinAToleranceOnTwoRanksMatchesOneRank) {
  ASSERT_EQ(world().size(), 2) << "run under mpirun -np 2";
  // run.rest_tolerance skips gas and parcels that rest within 1e-10 of the reference, which
  // changes bits (below: against exact skipping); each slab must skip what one grid skips.
  const Scene scene = reduced_quickstart();  // within the default 1e-10
  constexpr int kSteps = 150, kCheckpoint = 75;
  omp_set_num_threads(1);
  Simulation two(scene, &world());
  ASSERT_TRUE(two.decomposed());
  advance_steps(two, kCheckpoint);
  // The checkpoint two ranks write (rank 0's gathered snapshot), read back by every rank.
  const Snapshot written = two.snapshot();  // collective
  if (world().is_root()) write_checkpoint("slab_coupled_tolerance_75.h5", written);
  world().barrier();
  const Snapshot at_checkpoint = read_checkpoint("slab_coupled_tolerance_75.h5");
  advance_steps(two, kSteps - kCheckpoint);
  const Snapshot uninterrupted = two.snapshot();
  for (int threads : {1, 2}) {
    std::string names;
    EXPECT_EQ(differences(scene, kSteps, two, threads, names), 0)
        << threads << " thread(s): " << names;
  }
  if (!world().is_root()) return;
  // Every dataset of the checkpoint a run writes: one rank from the start, and one rank
  // continuing the two ranks' checkpoint.
  Simulation one(scene);
  advance_steps(one, kSteps);
  EXPECT_EQ(differing_datasets(one.snapshot(), uninterrupted), "") << "one rank";
  Simulation resumed(scene);
  resumed.restore(at_checkpoint);
  advance_steps(resumed, kSteps - kCheckpoint);
  EXPECT_EQ(differing_datasets(resumed.snapshot(), uninterrupted), "")
      << "one rank from the two ranks' checkpoint";
  // The tolerance mattered: exact skipping gives other bits and updates more gas cells.
  Simulation exact(reduced_quickstart({"run.exact=true"}));
  advance_steps(exact, kSteps);
  EXPECT_NE(differing_datasets(exact.snapshot(), uninterrupted), "");
  EXPECT_LT(one.gas().cell_updates(), exact.gas().cell_updates());
}

TEST(SlabCoupled, HybridRanksAndThreadsRestartFromACheckpointOfAnyLayout) {
  ASSERT_EQ(world().size(), 2) << "run under mpirun -np 2";
  // Two ranks of two threads each against one rank of one thread, in the default skipping:
  // each layout continues the other's checkpoint, and every dataset of the checkpoint it then
  // writes is the uninterrupted one-rank run's.
  const Scene scene = reduced_quickstart();
  constexpr int kSteps = 150, kCheckpoint = 75;
  const int before = omp_get_max_threads();
  Snapshot one_at_checkpoint, one_at_end;
  if (world().is_root()) {
    omp_set_num_threads(1);
    Simulation one(scene);
    advance_steps(one, kCheckpoint);
    one_at_checkpoint = one.snapshot();
    write_checkpoint("slab_coupled_hybrid_one_75.h5", one_at_checkpoint);
    advance_steps(one, kSteps - kCheckpoint);
    one_at_end = one.snapshot();
  }
  omp_set_num_threads(2);
  Simulation hybrid(scene, &world());
  ASSERT_TRUE(hybrid.decomposed());
  advance_steps(hybrid, kCheckpoint);
  const Snapshot hybrid_at_checkpoint = hybrid.snapshot();  // collective
  if (world().is_root()) write_checkpoint("slab_coupled_hybrid_two_75.h5", hybrid_at_checkpoint);
  advance_steps(hybrid, kSteps - kCheckpoint);
  const Snapshot hybrid_at_end = hybrid.snapshot();
  world().barrier();
  // Two ranks of two threads from the one-rank checkpoint, as `dustlift run --restart` reads it.
  Simulation hybrid_resumed(scene, &world());
  hybrid_resumed.restore(read_checkpoint("slab_coupled_hybrid_one_75.h5"));
  advance_steps(hybrid_resumed, kSteps - kCheckpoint);
  const Snapshot hybrid_from_one = hybrid_resumed.snapshot();
  omp_set_num_threads(before);
  if (!world().is_root()) return;
  EXPECT_EQ(differing_datasets(hybrid_at_checkpoint, one_at_checkpoint), "")
      << "2 ranks x 2 threads at the checkpoint";
  EXPECT_EQ(differing_datasets(hybrid_at_end, one_at_end), "") << "2 ranks x 2 threads";
  EXPECT_EQ(differing_datasets(hybrid_from_one, one_at_end), "")
      << "2 ranks x 2 threads from the one-rank checkpoint";
  omp_set_num_threads(1);
  Simulation one_resumed(scene);
  one_resumed.restore(read_checkpoint("slab_coupled_hybrid_two_75.h5"));
  advance_steps(one_resumed, kSteps - kCheckpoint);
  omp_set_num_threads(before);
  EXPECT_EQ(differing_datasets(one_resumed.snapshot(), one_at_end), "")
      << "1 rank x 1 thread from the hybrid checkpoint";
}

TEST(SlabCoupled, CutsThatFollowTheWorkChangeNothing) {
  // The cuts recomputed every 10 steps from the cells and parcels each column costs: the
  // parcels move to their new ranks with their contact lists, alpha_p with the gas. The
  // layer starts at 6 mm, so most parcels are right of the first cut (7.5 mm) and it moves.
  const Scene scene = reduced_quickstart({"run.rebalance_steps=10", "particles.layer.x_min=0.006"});
  constexpr int kSteps = 150;
  omp_set_num_threads(1);
  Simulation two(scene, &world());
  advance_steps(two, kSteps);
  EXPECT_GT(two.rebalances(), 0);
  std::string names;
  EXPECT_EQ(differences(scene, kSteps, two, 1, names), 0) << names;
}

}  // namespace
}  // namespace dustlift

int main(int argc, char** argv) {
  return dustlift::run_tests_on_every_rank(argc, argv);
}
