// The paper's dust layer as plain DEM on x-slabs of MPI ranks (docs/parallel.md):
// 60,000 parcels of 100 um (rho 980) in a channel 400 mm x 2 mm (walls at both ends and
// below, a lid at 2 mm), every parcel at 1 m/s in a random direction, k_n = 5e4 N/m,
// k_t = 2/7 k_n, friction 0.5, restitution 0.9: bench_dem_layer's reference setup with
// walls instead of the periodic join (a periodic channel cannot be split yet).
// Run under mpirun with any rank count (bench/mpi_dem_ranks.sh compares 1 and 2): equal
// cuts, STEPS timed steps (DUSTLIFT_BENCH_STEPS, default 4000) after one untimed step.
// Prints, from rank 0: wall seconds, parcel-steps per second, and per rank and step the
// doubles and messages it sent, parcels it handed over and the seconds in the exchange;
// then a checksum of the gathered final state (bit patterns of x, y, vx, vy, omega in the
// one-rank parcel order), equal on any rank count.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "bench/dem_reference_layer.hpp"
#include "solver/parallel/world.hpp"
#include "solver/parallel/parcel_slabs.hpp"

using namespace dustlift;

namespace {

std::uint64_t checksum(const ParcelSystem& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (const std::vector<double>* c : {&s.x, &s.y, &s.vx, &s.vy, &s.omega}) {
    for (double v : *c) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
  }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  const ParallelSession mpi(argc, argv);
  const auto world = make_world_communicator();
  const char* env = std::getenv("DUSTLIFT_BENCH_STEPS");
  const int steps = env != nullptr ? std::atoi(env) : 4000;
  const DemConfig cfg = reference_layer_config(false);
  ParcelSystem s = reference_layer(false);
  const int ranks = world->size();
  ParcelSlabs slabs(*world);
  if (ranks > 1) {
    std::vector<double> cuts;
    for (int q = 1; q < ranks; ++q) cuts.push_back(0.4 * q / ranks);
    slabs.split(s, cuts);
  }
  const double dt = s.stable_time_step();
  s.step(dt);  // first neighbour build (and the split) outside the timing
  const ParcelSlabs::Counters before = slabs.counters();
  world->barrier();
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < steps; ++n) s.step(dt);
  world->barrier();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ParcelSlabs::Counters& c = slabs.counters();
  const long long total = world->sum(static_cast<long long>(s.owned_count()));
  const std::vector<double> mine = {
      static_cast<double>(s.owned_count()),
      static_cast<double>(s.size() - s.owned_count()),
      static_cast<double>(c.doubles_sent - before.doubles_sent) / steps,
      static_cast<double>(c.messages - before.messages) / steps,
      static_cast<double>(c.migrated - before.migrated) / steps,
      (c.seconds - before.seconds)};
  std::vector<std::vector<double>> rows;
  world->gather(mine, rows);
  std::vector<double> state;
  s.pack_owned(state);
  std::vector<std::vector<double>> pieces;
  world->gather(state, pieces);
  if (world->is_root()) {
    ParcelSystem whole(cfg);
    whole.assign_packed(pieces);
    std::printf("ranks %d threads %d steps %d parcels %lld rebuilds %lld\n", ranks,
                omp_get_max_threads(), steps, total, s.neighbour_rebuilds());
    std::printf("wall %.3f s  parcel-steps/s %.4g\n", wall,
                static_cast<double>(total) * steps / wall);
    for (int q = 0; q < ranks; ++q) {
      const std::vector<double>& r = rows[static_cast<std::size_t>(q)];
      std::printf(
          "rank %d: owned %.0f ghosts %.0f | per step: %.1f doubles (%.0f B), %.2f messages | "
          "parcels "
          "handed over %.0f | exchange %.3f s\n",
          q, r[0], r[1], r[2], 8.0 * r[2], r[3], r[4] * steps, r[5]);
    }
    std::printf("checksum %016llx\n", static_cast<unsigned long long>(checksum(whole)));
  }
  return 0;
}
