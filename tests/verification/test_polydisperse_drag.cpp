// Two size classes in one uniform gas stream (one-way coupling, drag only): each parcel
// follows the drag ODE of a single particle of its own diameter, m_k dv/dt = beta_k(|u - v|)
// (u - v), integrated here by RK4 with the same drag curve (Clift & Gauvin, no corrections).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "solver/dem/parcel_system.hpp"
#include "solver/laws/drag.hpp"
#include "solver/sim/simulation.hpp"

using namespace dustlift;

namespace {

constexpr double kP = 101325.0, kT = 300.0, kU = 50.0, kR = 287.0, kMu = 1.8e-5, kRhoP = 980.0;

/// v(t) of one real particle of diameter d from rest in the frozen uniform stream (RK4).
double reference_velocity(double d, double t_end) {
  aero::GasAtParcel g;
  g.rho = kP / (kR * kT);
  g.u = {kU, 0.0};
  g.mu = kMu;
  g.c = std::sqrt(1.4 * kR * kT);
  const aero::VolumeFractionCorrection none{aero::VolumeFractionCorrection::Kind::None, 1.0};
  const double m = kRhoP * std::numbers::pi * d * d * d / 6.0;
  auto accel = [&](double v) {
    return aero::drag_coefficient(g, kU - v, d, false, none) * (kU - v) / m;
  };
  const int n = 20000;
  const double h = t_end / n;
  double v = 0.0;
  for (int k = 0; k < n; ++k) {
    const double a1 = accel(v), a2 = accel(v + 0.5 * h * a1), a3 = accel(v + 0.5 * h * a2),
                 a4 = accel(v + h * a3);
    v += h * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0;
  }
  return v;
}

}  // namespace

TEST(PolydisperseDrag, EachClassFollowsItsOwnSingleParticleOde) {
  const auto dir = std::filesystem::temp_directory_path() / "dustlift_polydisperse_drag";
  std::filesystem::create_directories(dir);
  // Two parcels of one parcel diameter, holding 40 um and 100 um particles, at different
  // heights (they never meet in the periodic channel).
  std::ofstream(dir / "layer.csv") << "x,y,diameter,particle_diameter\n0.001,0.001,100e-6,40e-6\n"
                                      "0.003,0.003,100e-6,100e-6\n";
  const std::string text = R"([run]
end_time = 1e-3
[grid]
x = { start = 0.0, end = 0.004, cells = 4 }
y = { start = 0.0, end = 0.004, cells = 4 }
[gas]
thermo = "calorically_perfect"
gamma = 1.4
gas_constant = 287.0
[gas.transport]
model = "constant"
viscosity = 1.8e-5
[boundary]
left = "periodic"
right = "periodic"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "uniform"
state = { p = 101325.0, T = 300.0, u = 50.0 }
[particles]
density = 980.0
diameter = 100e-6
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
arrangement = "file"
x_min = 0.0
x_max = 0.004
y_min = 0.0
y_max = 0.004
file = ")" + (dir / "layer.csv").string() +
                           R"("
[coupling]
two_way = false
compressibility_correction = false
volume_fraction_correction = "none"
magnus = false
pressure_force = false
rotation_torque = false
heat_transfer = false
)";
  Simulation sim(parse_scene(text, "poly.toml"));
  ASSERT_NE(sim.parcels(), nullptr);
  const double t_end = 1e-3;
  while (sim.time() < t_end * (1 - 1e-14)) sim.advance(t_end - sim.time());
  const ParcelSystem& ps = *sim.parcels();
  ASSERT_EQ(ps.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const double d = ps.real_diameter[k];
    const double expected = reference_velocity(d, sim.time());
    const double other = reference_velocity(d == 40e-6 ? 100e-6 : 40e-6, sim.time());
    std::printf("d = %g um: v = %.6f m/s, own ODE %.6f, the other class's %.6f\n", d * 1e6,
                ps.vx[k], expected, other);
    EXPECT_NEAR(ps.vx[k], expected, 3e-4 * expected) << d;   // observed: within 1e-4
    EXPECT_GT(std::fabs(other - expected), 0.2 * expected);  // the classes really differ
    EXPECT_NEAR(ps.vy[k], 0.0, 1e-12);
  }
  std::filesystem::remove_all(dir);
}
