// The paper scene (or any scene) for a fixed simulated interval, with the wall time of each
// phase of a step and the throughput counters:
//   gas cell-stage updates per second (those computed, and the full-grid equivalent),
//   coupled parcel-sub-steps per second (those stepped, and all parcels x sub-steps).
// The scene's own outputs (VTK, series, figures are not made) are written to a scratch folder
// so that their cost is part of the measurement, as in a real run.
//
//   build/release/bench/bench_paper_scene [SCENE] [--end 6e-4] [--threads 2] [--skip 1]
//                                         [--outputs 1] [--set key=value ...]
// Prints one line of key=value pairs (easy to grep or parse) and a readable summary.
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "insitu/outputs.hpp"
#include "solver/core/wait_policy.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/sim/simulation.hpp"

using namespace dustlift;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  reexec_with_default_wait_policy(argv);  // threads wait as in the dustlift program
  std::string scene_path = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/paper/vertical_shock.toml";
  double end = 6e-4;
  int threads = 2;
  bool skip = true, outputs = true;
  std::vector<std::string> overrides;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto next = [&]() -> std::string {
      if (k + 1 >= argc) {
        std::fprintf(stderr, "bench_paper_scene: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++k];
    };
    if (a == "--end") {
      end = std::stod(next());
    } else if (a == "--threads") {
      threads = std::stoi(next());
    } else if (a == "--skip") {
      skip = next() != "0";
    } else if (a == "--outputs") {
      outputs = next() != "0";
    } else if (a == "--set") {
      overrides.push_back(next());
    } else {
      scene_path = a;
    }
  }
  overrides.push_back("run.end_time=" + std::to_string(end));
  overrides.push_back(std::string("run.skip_at_rest=") + (skip ? "true" : "false"));
  omp_set_num_threads(threads);
  const Scene scene = load_scene(scene_path, overrides);
  const fs::path out = fs::temp_directory_path() / ("dustlift_bench_" + std::to_string(::getpid()));
  fs::create_directories(out);

  const auto t_setup = std::chrono::steady_clock::now();
  Simulation sim(scene);
  if (outputs) {
    for (auto& o : make_output_observers(scene, out.string())) sim.add_observer(std::move(o));
  }
  const double setup =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_setup).count();
  const auto t0 = std::chrono::steady_clock::now();
  sim.run(out.string());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fs::remove_all(out);

  const double steps = static_cast<double>(sim.step());
  const double cells = static_cast<double>(sim.grid().interior_cells());
  const double computed_cells = static_cast<double>(sim.gas().cell_updates());
  const auto& t = sim.timings();
  std::printf("scene=%s end=%g threads=%d skip=%d outputs=%d steps=%.0f setup_s=%.3f wall_s=%.3f",
              scene_path.c_str(), end, threads, skip ? 1 : 0, outputs ? 1 : 0, steps, setup, wall);
  std::printf(" gas_s=%.3f observers_s=%.3f", t.gas, t.observers);
  std::printf(
      " gas_cell_stages_per_s=%.4g gas_cell_stages_full_grid_per_s=%.4g computed_cell_share=%.4f",
      computed_cells / t.gas, 3.0 * cells * steps / t.gas, computed_cells / (3.0 * cells * steps));
  if (const ParcelSystem* p = sim.parcels()) {
    const auto& c = sim.coupling()->timings();
    const auto& d = p->timings();
    const double substeps = static_cast<double>(p->steps());
    const double stepped = static_cast<double>(p->parcel_substeps());
    const double coupled =
        c.sample + c.implicit_exchange + c.deposit + d.contacts + d.integrate + d.rebuild;
    std::printf(
        " sample_s=%.3f implicit_exchange_s=%.3f deposit_s=%.3f contacts_s=%.3f integrate_s=%.3f "
        "rebuild_s=%.3f",
        c.sample, c.implicit_exchange, c.deposit, d.contacts, d.integrate, d.rebuild);
    std::printf(
        " parcels=%zu substeps=%.0f rebuilds=%lld parcel_substeps_per_s=%.4g "
        "all_parcel_substeps_per_s=%.4g",
        p->size(), substeps, p->neighbour_rebuilds(), stepped / coupled,
        substeps * static_cast<double>(p->size()) / coupled);
  }
  std::printf("\n%s\n", wait_policy_description().c_str());
  return 0;
}
