#pragma once
// The DEM benchmarks' reference layer (docs/dem.md, "Benchmark"): 60,000 parcels of 100 um
// (rho 980, areal fraction 0.589) filling 400 mm x 2 mm between walls at y = 0 and 2 mm,
// every parcel at 1 m/s in a random direction; k_n = 5e4 N/m, k_t = 2/7 k_n, Coulomb
// friction 0.5, normal restitution 0.9, dt = 0.1 sqrt(m/k_n). Periodic in x (bench_dem_layer)
// or between end walls (bench_mpi_dem_layer_ranks: a periodic channel is not split).
#include <cmath>
#include <numbers>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/contact.hpp"

namespace dustlift {

inline DemConfig reference_layer_config(bool periodic) {
  constexpr double d = 100e-6, rho = 980.0, k_n = 5e4;
  const double m = rho * sphere_volume(d);
  DemConfig c;
  c.enabled = true;
  c.particle_diameter = c.parcel_diameter = d;
  c.density = rho;
  const double area = 0.4 * 0.002;
  // Exactly 60,000 parcels: areal fraction 60,000 pi d^2 / 4 / area = 0.589.
  c.layer = LayerConfig{
      0.0,  0.4, 0.0, 0.002, 60000.0 * disc_area(d) / area, 1, LayerArrangement::JitteredLattice,
      false};
  c.real_per_parcel = 1.0;  // plain DEM: one particle per parcel (no effect on the dynamics)
  c.contact = ContactParams{k_n, 2.0 / 7.0 * k_n, damping_for_restitution(m / 2, k_n, 0.9), 0.5};
  c.wall_contact = c.contact;
  c.domain = DemDomain{0.0, 0.4, 0.0, 0.002, true, true, !periodic, !periodic, periodic};
  c.courant = 0.1;  // dt = 0.1 sqrt(m / k_n), k_n > k_t
  return c;
}

/// The reference layer with its random velocities (seed 2024).
inline ParcelSystem reference_layer(bool periodic) {
  ParcelSystem s = make_layer_system(reference_layer_config(periodic));
  std::uint64_t seed = 2024;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double a = 2.0 * std::numbers::pi * uniform_from_seed(seed);
    s.vx[i] = std::cos(a);
    s.vy[i] = std::sin(a);
  }
  return s;
}

}  // namespace dustlift
