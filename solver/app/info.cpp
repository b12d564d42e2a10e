#include "solver/app/info.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "insitu/outputs.hpp"
#include "solver/app/cost_estimate.hpp"
#include "solver/app/layout_advice.hpp"
#include "solver/app/run_scene.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/parallel/world.hpp"
#include "solver/scene/resource_limits.hpp"

namespace dustlift {

double estimated_steps(const Simulation& sim) {
  const Grid2D& g = sim.grid();
  const GasPrimitives p = sim.gas().primitives();
  double su = 0.0, sv = 0.0;  // fastest signal along x and y anywhere at t = 0
  for (int j = 0; j < g.ny(); ++j) {
    for (int i = 0; i < g.nx(); ++i) {
      const double c = sim.gas().sound_speed(i, j);
      su = std::max(su, std::abs((*p.u)(i, j)) + c);
      sv = std::max(sv, std::abs((*p.v)(i, j)) + c);
    }
  }
  const double worst =
      sim.scene().gas.scheme.cfl / (su / g.x().min_width() + sv / g.y().min_width());
  const double dt = std::min(worst, sim.gas().stable_dt());  // the viscous limit too
  return std::ceil(sim.scene().run.end_time / dt);
}

namespace {

/// The dust cloud's filtered concentration: its box and lattice, its quantum against the
/// explosible band, and the warning the run's log gives when the quantum does not resolve the
/// band.
void print_dust_cloud(const Scene& scene, const ParcelSystem& parcels) {
  const DustCloudOptions o = dust_cloud_options(scene);
  double largest = 0.0;
  for (double m : parcels.mass) largest = std::max(largest, m);
  const double quantum = concentration_quantum(largest, o.filter_width);
  fmt::print(
      "dust cloud: filtered concentration in {:.4g} m boxes sliding by {:.3g} m; quantum (the "
      "largest parcel, {:.4g} kg/m, alone in a box) {:.4g} kg/m^3 = {:.3g} % of the explosible "
      "band [{:g}, {:g}] kg/m^3's lower edge\n",
      o.filter_width, o.filter_width / static_cast<double>(o.filter_subcells), largest, quantum,
      100.0 * quantum / o.explosible_lower, o.explosible_lower, o.explosible_upper);
  if (const std::string warning = quantum_warning(quantum, o); !warning.empty())
    fmt::print("{}\n", warning);
}

/// The expected wall time of the run on this machine's threads, and what it comes from.
void print_cost(const Scene& scene, const Simulation& sim, double steps, bool fresh_rates) {
  std::string how;
  const WorkRates r = measured_rates(scene, fresh_rates, how);
  const WorkForecast w = forecast_work(sim, steps);
  const bool skipping = scene.run.skip_at_rest;
  fmt::print(
      "cost: expected wall time ~ {} on {} thread{} (within about a factor 2; outputs not "
      "counted)\n",
      format_duration(expected_wall(w, r)), omp_get_max_threads(),
      omp_get_max_threads() == 1 ? "" : "s");
  fmt::print(
      "  work: {:.3g} gas cell-stages ({:.0f} % of the full grid{}), {:.3g} parcel-sub-steps "
      "and {:.3g} parcel samples ({:.0f} % of the parcels)\n",
      w.cell_stages, 100.0 * w.gas_share,
      skipping ? (scene.run.rest_tolerance > 0.0
                      ? ", skipping within run.rest_tolerance: the active region taken to follow "
                        "the shock, a lower bound"
                      : ", exact skipping at rest")
               : "",
      w.parcel_substeps, w.parcel_steps, 100.0 * w.parcel_share);
  fmt::print(
      "  rates: gas {:.3g} ns per cell-stage, DEM {:.3g} ns per parcel-sub-step, coupling "
      "{:.3g} ns per parcel sample; {}\n",
      1e9 * r.gas_per_cell_stage, 1e9 * r.dem_per_parcel_substep, 1e9 * r.coupling_per_parcel_step,
      how);
}

}  // namespace

void print_info(const Scene& scene, const Simulation& sim, CostEstimate cost) {
  const Grid2D& g = sim.grid();
  fmt::print("scene: {}  (run name '{}')\n", scene.source_file, scene.run.name);
  fmt::print("effects on:\n");
  for (const auto& e : sim.enabled_effects()) fmt::print("  - {}\n", e);
  fmt::print(
      "grid: {} x {} cells = {} cells; x in [{:g}, {:g}] m, y in [{:g}, {:g}] m; "
      "min dx = {:g} m, min dy = {:g} m\n",
      g.nx(), g.ny(), g.interior_cells(), g.x().start(), g.x().end(), g.y().start(), g.y().end(),
      g.x().min_width(), g.y().min_width());
  const ParcelSystem* parcels = sim.parcels();
  if (parcels != nullptr) {
    fmt::print("parcels: {}; DEM sub-step (eq. 18, nu_DEM {:g}) = {:.4g} s, ~{} per CFD step\n",
               parcels->size(), scene.particles.courant, parcels->stable_time_step(),
               parcels->substeps_for(sim.gas().stable_dt()));
    fmt::print("{}\n", describe_layer(scene.particles));
    if (layer_settles(scene.particles.layer))
      fmt::print("{}\n", describe_bed(*parcels, scene.particles.layer));
    if (scene.output.dust_cloud) print_dust_cloud(scene, *parcels);
  } else {
    fmt::print("parcels: 0 (gas only)\n");
  }
  fmt::print("memory: about {} (estimate)\n",
             format_bytes(estimated_run_bytes(
                 static_cast<double>(g.interior_cells()),
                 parcels != nullptr ? static_cast<double>(parcels->size()) : 0.0)));
  // How it can run in parallel (docs/parallel.md): threads always, ranks when built with MPI.
  // Parcels are split over ranks with the grid, except in a periodic channel.
  const bool periodic = scene.gas.boundary.left == BoundaryKind::Periodic;
  fmt::print("parallel: OpenMP up to {} threads (--threads); {}\n", omp_get_max_threads(),
             !built_with_mpi() ? "MPI: not in this build"
             : parcels != nullptr && periodic
                 ? "MPI: in this build, but a periodic channel with particles runs on one rank"
             : parcels != nullptr
                 ? "MPI: mpirun -np N dustlift run SCENE runs x-slabs of this grid, each rank with "
                   "the parcels in its slab"
                 : "MPI: mpirun -np N dustlift run SCENE runs x-slabs of this grid");
  const LayoutAdvice layout =
      recommend_layout({omp_get_max_threads(), built_with_mpi(), parcels != nullptr && periodic});
  fmt::print("layout: {} rank x {} thread{} (`{}`): {}\n", layout.ranks, layout.threads,
             layout.threads == 1 ? "" : "s", layout.command, layout.reason);
  const double dt0 = sim.gas().stable_dt();
  const double steps = estimated_steps(sim);
  fmt::print(
      "time: end {:g} s; initial dt (eq. 17, CFL {:g}) = {:.4g} s; estimated steps ~ {:.0f} "
      "(the fastest gas at t = 0 on the smallest cells; {:.0f} at the initial dt)\n",
      scene.run.end_time, scene.gas.scheme.cfl, dt0, steps, std::ceil(scene.run.end_time / dt0));
  if (cost != CostEstimate::Off) print_cost(scene, sim, steps, cost == CostEstimate::Fresh);
  fmt::print("\n{}", scene.resolved_toml);
}

}  // namespace dustlift
