// What a decomposed step spends talking (docs/parallel.md's scaling model), under
// `mpirun -np 2 build/release/bench/bench_mpi_halo_exchange [GRID]`: the paper grid's slab
// halo exchange (the six fields of a stage: rho, u, v, p, T and the edge activity, two ghost
// columns of all 164 rows each way), and the collectives a step makes (the time step's min,
// the fault agreement of each stage). Medians over many repetitions, in microseconds.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/parallel/world.hpp"
#include "solver/parallel/slab_decomposition.hpp"
#include "solver/parallel/slab_halo.hpp"

using namespace dustlift;

namespace {

template <class F>
double median_us(const Communicator& comm, int reps, F&& f) {
  std::vector<double> t;
  for (int k = 0; k < reps; ++k) {
    comm.barrier();
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - a).count());
  }
  std::nth_element(t.begin(), t.begin() + reps / 2, t.end());
  return comm.min(-t[static_cast<std::size_t>(reps / 2)]) * -1.0;  // the slowest rank's median
}

}  // namespace

int main(int argc, char** argv) {
  const ParallelSession mpi(argc, argv);
  const auto comm = make_world_communicator();
  // The paper grid (vertical_shock.toml): 1900 x 160 cells, 2 ghost layers.
  AxisSpec x{-0.4, 0.4, 0, 250e-6, 0.0, 0.4, 300, 0};
  AxisSpec y{-0.002, 0.050, 0, 250e-6, -0.002, 0.032, 0, 24};
  const Grid2D whole(x, y, 2);
  const std::vector<double> cost(static_cast<std::size_t>(whole.nx()), 1.0);
  const SlabLayout layout{balanced_slabs(cost, comm->size(), 2), comm->rank(), false};
  const Grid2D slab = whole.slice_x(layout.first_column(), layout.end_column());
  std::vector<Field2D> fields(6, Field2D(slab, 1.0));
  std::vector<Field2D*> pointers;
  for (auto& f : fields) pointers.push_back(&f);
  SlabHalo halo(*comm, layout, slab);
  const int reps = argc > 1 ? std::atoi(argv[1]) : 2000;
  for (int k = 0; k < 50; ++k) halo.exchange_columns(pointers);  // warm-up
  const long long d0 = halo.doubles_sent(), m0 = halo.messages_sent();
  const double exchange = median_us(*comm, reps, [&] { halo.exchange_columns(pointers); });
  const double per_exchange_bytes = 8.0 * static_cast<double>(halo.doubles_sent() - d0) /
                                    static_cast<double>(halo.messages_sent() - m0);
  double sink = 0.0;
  const double allreduce = median_us(*comm, reps, [&] { sink += comm->min(1.0); });
  const double agreement =
      median_us(*comm, reps, [&] { sink += static_cast<double>(comm->first_nonempty("").size()); });
  if (comm->is_root()) {
    std::printf("ranks %d, slab %d x %d cells of the paper grid\n", comm->size(), slab.nx(),
                slab.ny());
    std::printf("halo exchange (6 fields, both ways): %.1f us median; %.0f bytes per message\n",
                exchange, per_exchange_bytes);
    std::printf("allreduce (time step min): %.2f us median\n", allreduce);
    std::printf("fault agreement (first_nonempty, no fault): %.2f us median\n", agreement);
    std::printf("(checksum %g)\n", sink);
  }
  return 0;
}
