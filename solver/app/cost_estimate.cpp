#include "solver/app/cost_estimate.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "solver/app/version.hpp"
#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/gas/shock_relations.hpp"
#include "solver/sim/simulation.hpp"

namespace fs = std::filesystem;

namespace dustlift {
namespace {

/// Exact skipping lets the rounding noise of the shocked region creep ahead of the shock at
/// about four cells per step (docs/performance.md, "Skipping within a tolerance").
constexpr double kNoiseCellsPerStep = 4.0;

/// The first line of /proc/cpuinfo's "model name" (the cache is per CPU).
std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  }
  return "unknown CPU";
}

fs::path cache_file() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const fs::path base = xdg != nullptr && *xdg != '\0' ? fs::path(xdg)
                        : home != nullptr              ? fs::path(home) / ".cache"
                                                       : fs::temp_directory_path();
  return base / "dustlift" / "rates.txt";
}

/// What the rates depend on: the scene, the threads, the code and the CPU.
std::string cache_key(const Scene& scene) {
  const std::size_t h =
      std::hash<std::string>{}(scene.resolved_toml + "\n" + code_version() + "\n" + cpu_model());
  return fmt::format("{:016x}-t{}", h, omp_get_max_threads());
}

std::string threads_text() {
  const int n = omp_get_max_threads();
  return fmt::format("{} thread{}", n, n == 1 ? "" : "s");
}

constexpr double kCacheSeconds = 24.0 * 3600.0;  // machines of one kind drift from day to day

bool read_cached(const std::string& key, WorkRates& r, double& age) {
  std::ifstream f(cache_file());
  const double now = static_cast<double>(std::time(nullptr));
  bool found = false;
  for (std::string line; std::getline(f, line);) {
    std::istringstream s(line);
    std::string k;
    double when = 0.0;
    WorkRates read;
    if (!(s >> k >> when >> read.gas_per_cell_stage >> read.dem_per_parcel_substep >>
          read.coupling_per_parcel_step))
      continue;
    if (k == key && now - when < kCacheSeconds) {
      r = read;
      age = now - when;
      found = true;
    }
  }
  return found;
}

/// Adds the rates under `key`, dropping that key's earlier line and every line older than the
/// cache keeps (the file stays one line per scene and thread count measured within a day).
void write_cached(const std::string& key, const WorkRates& r) {
  std::error_code ec;
  const fs::path file = cache_file();
  fs::create_directories(file.parent_path(), ec);
  const auto now = std::time(nullptr);
  std::string kept;
  {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
      std::istringstream s(line);
      std::string k;
      double when = 0.0;
      if (s >> k >> when && k != key && static_cast<double>(now) - when < kCacheSeconds)
        kept += line + "\n";
    }
  }
  std::ofstream f(file, std::ios::trunc);
  if (f)
    f << kept
      << fmt::format("{} {} {:.6e} {:.6e} {:.6e}\n", key, now, r.gas_per_cell_stage,
                     r.dem_per_parcel_substep, r.coupling_per_parcel_step);
}

/// Steps the scene with nothing skipped until `budget` wall seconds or `max_steps` steps
/// have passed after one warm-up step, and divides each part's time by its work.
WorkRates measure(Scene scene, double budget, int max_steps) {
  scene.run.skip_at_rest = false;
  scene.run.rest_tolerance = 0.0;
  Simulation sim(scene);
  const double dt_max = scene.run.end_time;
  sim.advance(dt_max);  // the first neighbour list and the first fields
  const auto gas0 = sim.timings().gas;
  const long long cells0 = sim.gas().cell_updates();
  double dem0 = 0.0, coupling0 = 0.0;
  long long substeps0 = 0;
  const auto dem_time = [&] {
    const auto& d = sim.parcels()->timings();
    return d.contacts + d.integrate + d.rebuild;
  };
  const auto coupling_time = [&] {
    const auto& c = sim.coupling()->timings();
    return c.sample + c.implicit_exchange + c.deposit;
  };
  if (sim.parcels() != nullptr) {
    dem0 = dem_time();
    coupling0 = coupling_time();
    substeps0 = sim.parcels()->parcel_substeps();
  }
  const auto start = std::chrono::steady_clock::now();
  int steps = 0;
  while (steps < max_steps &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < budget) {
    sim.advance(dt_max);
    ++steps;
  }
  WorkRates r;
  const double cells = static_cast<double>(sim.gas().cell_updates() - cells0);
  if (cells > 0.0) r.gas_per_cell_stage = (sim.timings().gas - gas0) / cells;
  if (sim.parcels() != nullptr && steps > 0) {
    const double substeps = static_cast<double>(sim.parcels()->parcel_substeps() - substeps0);
    if (substeps > 0.0) r.dem_per_parcel_substep = (dem_time() - dem0) / substeps;
    r.coupling_per_parcel_step =
        (coupling_time() - coupling0) /
        (static_cast<double>(steps) * static_cast<double>(sim.parcels()->size()));
  }
  return r;
}

}  // namespace

double mean_share_behind(const std::vector<double>& x, double x0, double steps,
                         double advance_per_step) {
  if (x.empty() || !(steps > 0.0)) return 1.0;
  // A point at x is behind the front from step (x - x0) / advance on: it counts for the
  // remaining share of the steps.
  double sum = 0.0;
  for (double xp : x) {
    const double reached = advance_per_step > 0.0 ? std::max(0.0, (xp - x0) / advance_per_step)
                                                  : (xp <= x0 ? 0.0 : steps);
    sum += std::clamp((steps - reached) / steps, 0.0, 1.0);
  }
  return sum / static_cast<double>(x.size());
}

WorkForecast forecast_work(const Simulation& sim, double steps) {
  const Scene& scene = sim.scene();
  const Grid2D& g = sim.grid();
  WorkForecast w;
  w.steps = steps;
  const InitialCondition& ic = scene.initial;
  const bool shock = ic.kind == InitialCondition::Kind::Shock && ic.axis == 'x';
  if (scene.run.skip_at_rest && shock && steps > 0.0) {
    const double speed = normal_shock(ic.state, ic.mach, scene.gas.thermo, 'x').shock_speed;
    const double shock_per_step = speed * scene.run.end_time / steps;
    const double noise_per_step = kNoiseCellsPerStep * g.x().min_width();
    const double per_step =
        scene.run.rest_tolerance > 0.0 ? shock_per_step : std::max(shock_per_step, noise_per_step);
    std::vector<double> columns(static_cast<std::size_t>(g.nx()));
    for (int i = 0; i < g.nx(); ++i) columns[static_cast<std::size_t>(i)] = g.x().center(i);
    // The stencils reach two cells beyond the front.
    w.gas_share =
        mean_share_behind(columns, ic.position + 2.0 * g.x().min_width(), steps, per_step);
    if (sim.parcels() != nullptr)
      w.parcel_share = mean_share_behind(sim.parcels()->x, ic.position, steps, per_step);
  }
  w.cell_stages = 3.0 * static_cast<double>(g.interior_cells()) * steps * w.gas_share;
  if (const ParcelSystem* p = sim.parcels(); p != nullptr) {
    const double parcels = static_cast<double>(p->size());
    w.parcel_steps = parcels * steps * w.parcel_share;
    w.parcel_substeps =
        w.parcel_steps * static_cast<double>(p->substeps_for(sim.gas().stable_dt()));
  }
  return w;
}

WorkRates measured_rates(const Scene& scene, bool fresh, std::string& how) {
  const std::string key = cache_key(scene);
  WorkRates r;
  double age = 0.0;
  if (!fresh && read_cached(key, r, age)) {
    how = fmt::format("rates measured {:.0f} min ago on this machine ({}; cached in {})",
                      age / 60.0, threads_text(), cache_file().string());
    return r;
  }
  const auto start = std::chrono::steady_clock::now();
  r = measure(scene, 2.0, 200);
  write_cached(key, r);
  how = fmt::format("rates measured now on this machine in {:.1f} s ({}; cached for a day in {})",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                    threads_text(), cache_file().string());
  return r;
}

}  // namespace dustlift
