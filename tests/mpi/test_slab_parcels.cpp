// The DEM parcels on x-slabs over MPI ranks, run by ctest as `mpirun -np 2`:
// both ranks run the decomposed system, rank 0 gathers it and compares it bit for bit with
// the same system run on one rank in-process (positions, velocities, spins, forces, the
// parcel order, every neighbour slot and its tangential history, the wall history).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "mpi/mpi_test_main.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/parallel/world.hpp"
#include "solver/parallel/parcel_slabs.hpp"

namespace dustlift {
namespace {

const Communicator& world() {
  static const std::unique_ptr<Communicator> w = make_world_communicator();
  return *w;
}

constexpr double kCut = 5e-3;  // m: rank 0 | rank 1

// A soft contact law (k_n = 500 N/m) so that a sub-step is 1e-7 s and parcels cross several
// diameters in a few thousand steps; strong gravity keeps stacked parcels pressed together.
DemConfig box_config(double x_max = 0.01) {
  DemConfig c;
  c.enabled = true;
  c.contact.k_n = 500.0;
  c.contact.k_t = 100.0;
  c.contact.damping = 1e-6;
  c.contact.friction = 0.5;
  c.wall_contact = c.contact;
  c.domain = {0.0, x_max, -0.002, 0.002, true, true, true, true, false};
  c.gravity_y = -2000.0;
  return c;
}

ParcelInit parcel(double x, double y, double vx, double vy, double omega = 0.0) {
  ParcelInit p;
  p.x = x;
  p.y = y;
  p.vx = vx;
  p.vy = vy;
  p.omega = omega;
  return p;
}

// A packed bed of 36 x 4 touching parcels on the floor across the cut (jittered a little),
// drifting towards rank 1 until the floor's friction stops it, two
// stacked pairs sliding over it towards the cut from either side, an oblique head-on
// collision at the cut, and one fast parcel (a fast skin, searched over a wide block) shot
// into the bed from rank 1's side.
void add_scene(ParcelSystem& s) {
  unsigned state = 12345u;
  auto jitter = [&state] {
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) & 0xffff) / 65535.0 - 0.5;
  };
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 36; ++col) {
      const double x = 3.2e-3 + col * 100.5e-6 + 0.4e-6 * jitter();
      const double y = -1.95e-3 + row * 100e-6;
      s.add_parcel(parcel(x, y, 0.5 + 0.05 * jitter(), 0.05 * jitter(), 200.0 * jitter()));
    }
  }
  // Stacked pairs sliding over the bed towards the cut, one from each side.
  s.add_parcel(parcel(4.7e-3, -1.55e-3, 2.5, 0.0));
  s.add_parcel(parcel(4.7e-3, -1.55e-3 + 100e-6, 2.5, 0.0));
  s.add_parcel(parcel(5.3e-3, -1.55e-3, -3.0, 0.0));
  s.add_parcel(parcel(5.3e-3, -1.55e-3 + 100e-6, -3.0, 0.0));
  // Head-on, offset by 40 um in y, meeting near the cut.
  s.add_parcel(parcel(4.6e-3, 0.5e-3, 1.5, 0.0));
  s.add_parcel(parcel(5.4e-3, 0.54e-3, -1.5, 0.0));
  // A fast parcel from rank 1's side, diving into the bed.
  s.add_parcel(parcel(6.5e-3, -1.2e-3, -12.0, -2.0));
}

void run(ParcelSystem& s, int steps, const std::vector<std::pair<int, double>>& moves = {},
         ParcelSlabs* slabs = nullptr) {
  const double dt = s.stable_time_step();
  for (int k = 0; k < steps; ++k) {
    for (const auto& [at, cut] : moves) {
      if (k == at && slabs != nullptr) slabs->set_cuts({cut});
    }
    s.step(dt);
  }
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Gathers the decomposed system on rank 0 (pack_owned, assign_packed) and compares it with a
// one-rank run of the same scene. Returns the number of differing arrays (rank 0).
using Scene = void (*)(ParcelSystem&);

int differences_from_one_rank(const ParcelSystem& decomposed, int steps,
                              const std::vector<std::pair<int, double>>& moves, std::string& report,
                              Scene scene = add_scene, double x_max = 0.01) {
  std::vector<double> mine;
  decomposed.pack_owned(mine);
  std::vector<std::vector<double>> pieces;
  world().gather(mine, pieces);
  if (!world().is_root()) return 0;
  ParcelSystem gathered(box_config(x_max));
  gathered.assign_packed(pieces);
  ParcelSystem serial(box_config(x_max));
  scene(serial);
  run(serial, steps, moves);
  int differ = 0;
  auto check = [&](bool same, const std::string& what) {
    if (!same) {
      ++differ;
      report += what + " ";
    }
  };
  check(gathered.size() == serial.size(), "size");
  if (gathered.size() != serial.size()) return differ;
  gathered.for_each_column_pair(
      serial, [&](const ParcelColumnSpec& c, const auto& mine, const auto& theirs) {
        if (ParcelTable::is_state(c)) check(same_bits(mine, theirs), c.name);
      });
  check(same_bits(gathered.id, serial.id), "id (parcel order)");
  check(same_bits(gathered.wall_delta, serial.wall_delta), "wall_delta");
  check(same_bits(gathered.nbr_offset, serial.nbr_offset), "nbr_offset");
  check(same_bits(gathered.nbr_index, serial.nbr_index), "nbr_index");
  check(same_bits(gathered.nbr_delta, serial.nbr_delta), "nbr_delta");
  check(same_bits(gathered.x_build, serial.x_build), "x_build");
  check(same_bits(gathered.half_skin, serial.half_skin), "half_skin");
  return differ;
}

TEST(SlabParcels, ABedAcrossTheCutMatchesOneRankBitForBit) {
  ASSERT_EQ(world().size(), 2) << "run under mpirun -np 2";
  constexpr int kSteps = 3000;
  ParcelSystem s(box_config());
  add_scene(s);
  ParcelSlabs slabs(world());
  slabs.split(s, {kCut});
  run(s, kSteps);
  const auto& c = slabs.counters();
  // Parcels left each rank for the other, and copies went both ways.
  EXPECT_GT(c.migrated, 0) << "rank " << world().rank();
  EXPECT_GT(c.copies_sent, 0) << "rank " << world().rank();
  EXPECT_EQ(world().sum(static_cast<long long>(s.owned_count())), 151);
  std::string report;
  EXPECT_EQ(differences_from_one_rank(s, kSteps, {}, report), 0) << report;
  // The cell sort renumbered the parcels across ranks on the way.
  EXPECT_GE(s.data_permutations(), 3);
}

// Two parcels stacked on the floor slide across the cut at 5 m/s, to the right from rank 0
// or to the left from rank 1: the lower one slides on the floor all the way (a wall
// elongation it must carry to its new owner), the upper one rides on it.
void add_stack_moving_right(ParcelSystem& s) {
  s.add_parcel(parcel(4.85e-3, -1.95e-3, 5.0, 0.0));
  s.add_parcel(parcel(4.85e-3, -1.85e-3, 5.0, 0.0));
}
void add_stack_moving_left(ParcelSystem& s) {
  s.add_parcel(parcel(5.15e-3, -1.95e-3, -5.0, 0.0));
  s.add_parcel(parcel(5.15e-3, -1.85e-3, -5.0, 0.0));
}

TEST(SlabParcels, ATouchingPairCrossesTheCutEitherWayWithItsHistory) {
  constexpr int kSteps = 1500;
  for (const auto& [scene, from] :
       {std::pair<Scene, int>{add_stack_moving_right, 0}, {add_stack_moving_left, 1}}) {
    ParcelSystem s(box_config());
    scene(s);
    ParcelSlabs slabs(world());
    slabs.split(s, {kCut});
    run(s, kSteps);
    // The rank the pair left handed it over with its floor elongation.
    if (world().rank() == from) {
      EXPECT_GE(slabs.counters().migrated_with_history, 1) << "from rank " << from;
      EXPECT_EQ(s.owned_count(), 0u) << "from rank " << from;
    }
    std::string report;
    EXPECT_EQ(differences_from_one_rank(s, kSteps, {}, report, scene), 0)
        << report << "from rank " << from;
  }
}

TEST(SlabParcels, MovingCutsChangeNothing) {
  constexpr int kSteps = 2500;
  const std::vector<std::pair<int, double>> moves = {{700, 3.6e-3}, {1500, 6.1e-3}, {2000, 4.9e-3}};
  ParcelSystem s(box_config());
  add_scene(s);
  ParcelSlabs slabs(world());
  slabs.split(s, {kCut});
  run(s, kSteps, moves, &slabs);
  std::string report;
  EXPECT_EQ(differences_from_one_rank(s, kSteps, moves, report), 0) << report;
}

TEST(SlabParcels, ARankWithoutParcelsTakesPart) {
  // Every parcel starts on rank 0's side; rank 1 holds nothing until the fast one arrives.
  constexpr int kSteps = 1500;
  const std::vector<std::pair<int, double>> moves = {{0, 9.5e-3}};
  ParcelSystem s(box_config());
  add_scene(s);
  ParcelSlabs slabs(world());
  slabs.split(s, {9.5e-3});
  run(s, kSteps, moves, &slabs);
  std::string report;
  EXPECT_EQ(differences_from_one_rank(s, kSteps, moves, report), 0) << report;
}

TEST(SlabParcels, ASystemSplitBetweenRebuildsContinuesBitwise) {
  // A checkpoint's restart on two ranks: every rank holds the one-rank system after 700
  // steps (lists, histories, skins), splits it and continues.
  constexpr int kAfter = 1500;
  ParcelSystem s(box_config());
  add_scene(s);
  run(s, 700);
  int before = 700;  // on to a step that leaves no rebuild pending: the lists are current
  const double dt = s.stable_time_step();
  while (s.internals().needs_rebuild) {
    s.step(dt);
    ++before;
  }
  ParcelSlabs slabs(world());
  slabs.split(s, {kCut});
  EXPECT_LT(s.owned_count(), s.size());  // rank copies from the start
  run(s, kAfter);
  std::string report;
  EXPECT_EQ(differences_from_one_rank(s, before + kAfter, {}, report), 0) << report;
}

// The reference layer of the DEM benchmark cut to 40 mm (6,000 parcels: the loops run as
// parallel regions) with 1 m/s random velocities, split at 20 mm.
DemConfig layer_config() {
  DemConfig c = box_config(0.04);
  c.contact.k_n = 5e4;
  c.contact.k_t = 2.0 / 7.0 * c.contact.k_n;
  c.contact.damping = 1e-4;
  c.wall_contact = c.contact;
  c.gravity_y = 0.0;
  c.domain.y_max = 0.002;
  c.domain.y_min = 0.0;
  c.layer.x_min = 0.0;
  c.layer.x_max = 0.04;
  c.layer.y_min = 0.0;
  c.layer.y_max = 0.002;
  c.layer.volume_fraction = 0.589;
  c.real_per_parcel = 1.0;
  return c;
}

void add_layer(ParcelSystem& s) {
  ParcelSystem made = make_layer_system(layer_config());
  unsigned state = 7u;
  for (std::size_t i = 0; i < made.size(); ++i) {
    state = state * 1103515245u + 12345u;
    const double a = 6.283185307179586 * static_cast<double>((state >> 8) & 0xffff) / 65536.0;
    s.add_parcel(parcel(made.x[i], made.y[i], std::cos(a), std::sin(a)));
  }
}

TEST(SlabParcels, AThousandsStrongLayerWithCopiedColumnsMatchesOneRank) {
  constexpr int kSteps = 400;
  ParcelSystem s(layer_config());
  add_layer(s);
  ASSERT_GT(s.size(), kParallelMinimum);
  const ParcelColumn tag = s.attach_column({"tag", "1", false, false});
  ParcelSlabs slabs(world());
  slabs.set_copy_margin(3e-4);
  slabs.split(s, {0.02});
  const double dt = s.stable_time_step();
  for (int k = 0; k < kSteps; ++k) s.step(dt);
  // A column the owners fill reaches the rank copies.
  std::vector<double>& t = s.column(tag);
  for (std::size_t i = 0; i < s.size(); ++i) t[i] = s.is_rank_copy(i) ? -1.0 : 1.5 * s.id[i];
  const ParcelColumn refreshed[] = {tag};
  s.refresh_rank_copies(refreshed);
  std::size_t copies = 0, wrong = 0;
  double farthest = 0.0;  // of the rank copies from the cut
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.is_rank_copy(i)) continue;
    ++copies;
    wrong += t[i] != 1.5 * s.id[i] ? 1 : 0;
    farthest = std::max(farthest, std::abs(s.x[i] - 0.02));
  }
  EXPECT_GT(copies, 0u);
  EXPECT_EQ(wrong, 0u);
  // The margin widens the band of copies beyond the contact reach (0.2-0.3 mm here without it).
  EXPECT_GT(farthest, 4.5e-4) << farthest;
  std::vector<double> mine;
  s.pack_owned(mine);
  std::vector<std::vector<double>> pieces;
  world().gather(mine, pieces);
  if (world().is_root()) {
    ParcelSystem gathered(layer_config());
    gathered.attach_column({"tag", "1", false, false});
    gathered.assign_packed(pieces);
    ParcelSystem serial(layer_config());
    add_layer(serial);
    for (int k = 0; k < kSteps; ++k) serial.step(dt);
    ASSERT_EQ(gathered.size(), serial.size());
    EXPECT_TRUE(same_bits(gathered.x, serial.x));
    EXPECT_TRUE(same_bits(gathered.vy, serial.vy));
    EXPECT_TRUE(same_bits(gathered.omega, serial.omega));
    EXPECT_TRUE(same_bits(gathered.nbr_delta, serial.nbr_delta));
  }
}

TEST(SlabParcels, AFailureOnOneRankIsEveryRanksMessage) {
  ParcelSystem s(box_config());
  add_scene(s);
  ParcelSlabs slabs(world());
  slabs.split(s, {kCut});
  const std::string local = world().rank() == 1 ? "parcel id 7: velocity not finite" : "";
  EXPECT_EQ(world().first_nonempty(local), "parcel id 7: velocity not finite");
}

}  // namespace
}  // namespace dustlift

int main(int argc, char** argv) {
  return dustlift::run_tests_on_every_rank(argc, argv);
}
