// A single sphere passed by a shock (Ms 1.22 in air, the case of Tanno et al. 2003 that Parmar,
// Haselbacher & Balachandar 2009 model): the inviscid force on a fixed sphere from the
// undisturbed flow, the pressure-gradient force and the added mass's fluid part, averaged over
// the sphere (coupling.finite_size), against its closed form for a shock much thinner than the
// sphere. With the shock at x_s from the centre (radius a) the undisturbed pressure acts on the
// part of the sphere behind it, F_p = Delta p pi (a^2 - x_s^2), and the added mass's
// C_M V_p <D(rho u)/Dt> has the same shape with Delta p replaced by U_s K, where along the
// steady shock profile (rho (U_s - u) = rho_1 U_s, p = p_1 + rho_1 U_s u)
//   K = int_0^{u_2} C_M(u / c(u)) rho_1 U_s / (U_s - u) du      (D(rho u)/Dt = (u - U_s) d(rho
//   u)/dx).
// Peak pi a^2 (Delta p + U_s K) when the shock crosses the centre; impulse V_p (Delta p / U_s + K).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "solver/dem/parcel_system.hpp"
#include "solver/laws/added_mass.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"

using namespace dustlift;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = std::numbers::pi;

// The sphere (d = 2 mm, 10 cells across) sits at x = 20 mm, the shock starts at 10 mm.
const std::string kScene = R"([run]
end_time = 34e-6
[grid]
x = { start = 0.0, end = 0.04, cells = 200 }
y = { start = 0.0, end = 0.004, cells = 20 }
[gas]
thermo = "calorically_perfect"
gamma = 1.4
gas_constant = 287.05
[gas.scheme]
cfl = 0.4
[boundary]
left = "inflow"
right = "outflow"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "shock"
mach = 1.22
position = 0.010
state = { p = 101325.0, T = 293.15 }
[particles]
diameter = 2e-3
density = 1e9
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
x_min = 0.019
x_max = 0.021
y_min = 0.001
y_max = 0.003
arrangement = "lattice"
volume_fraction = 0.5
[coupling]
two_way = false
drag = false
magnus = false
rotation_torque = false
heat_transfer = false
pressure_force = true
added_mass = true
added_mass_volume_fraction = "none"
finite_size = true
influence_width = 0.0
[output]
vtk = false
dust_cloud = false
)";

struct ShockState {
  double p1, rho1, c1, us, u2, dp;
};

ShockState shock(double ms) {
  const double g = 1.4, r = 287.05, p1 = 101325.0, t1 = 293.15;
  const double rho1 = p1 / (r * t1), c1 = std::sqrt(g * r * t1), us = ms * c1;
  const double p2 = p1 * (1.0 + 2.0 * g / (g + 1.0) * (ms * ms - 1.0));
  const double rho2 = rho1 * (g + 1.0) * ms * ms / ((g - 1.0) * ms * ms + 2.0);
  return {p1, rho1, c1, us, us * (1.0 - rho1 / rho2), p2 - p1};
}

/// K of the header: the added mass's impulse per volume along the steady profile (midpoint rule,
/// 20,000 intervals).
double added_mass_integral(const ShockState& s) {
  const int n = 20000;
  double k = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) * s.u2 / n;
    const double rho = s.rho1 * s.us / (s.us - u), p = s.p1 + s.rho1 * s.us * u;
    const double c = std::sqrt(1.4 * p / rho);
    const double c_m =
        aero::added_mass_coefficient(u / c, 0.0, aero::AddedMassVolumeFraction::None);
    k += c_m * s.rho1 * s.us / (s.us - u) * (s.u2 / n);
  }
  return k;
}

}  // namespace

TEST(SingleSphereShock, InviscidForcePeakAndImpulseAgainstTheUndisturbedFlowsClosedForm) {
  const fs::path dir =
      fs::temp_directory_path() / ("dustlift_sphere_shock_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.toml") << kScene;
  const Scene scene = load_scene((dir / "scene.toml").string());
  Simulation sim(scene);
  const ParcelSystem& ps = *sim.parcels();
  ASSERT_EQ(ps.size(), 1u);
  const ParcelColumn fp = ps.find_part(ForcePart::Pressure, 0);
  const ParcelColumn fa = ps.find_part(ForcePart::AddedMass, 0);
  double peak = 0.0, peak_p = 0.0, impulse = 0.0, impulse_p = 0.0;
  while (sim.time() < scene.run.end_time) {
    const double t0 = sim.time();
    sim.advance(scene.run.end_time - t0);
    const double dt = sim.time() - t0;
    // The forces the parcel felt over the step (frozen over it; per real particle).
    const double f_p = ps.column(fp)[0], f_a = ps.column(fa)[0];
    peak = std::max(peak, f_p + f_a);
    peak_p = std::max(peak_p, f_p);
    impulse += (f_p + f_a) * dt;
    impulse_p += f_p * dt;
  }
  const ShockState s = shock(1.22);
  const double a = 1e-3, vp = 4.0 / 3.0 * kPi * a * a * a, k = added_mass_integral(s);
  const double expected_peak_p = kPi * a * a * s.dp, expected_impulse_p = vp * s.dp / s.us;
  const double expected_peak = kPi * a * a * (s.dp + s.us * k);
  const double expected_impulse = vp * (s.dp / s.us + k);
  std::printf(
      "pressure part: peak %.4g N (closed form %.4g), impulse %.4g N s (%.4g); with the added "
      "mass: "
      "peak %.4g N (%.4g), impulse %.4g N s (%.4g)\n",
      peak_p, expected_peak_p, impulse_p, expected_impulse_p, peak, expected_peak, impulse,
      expected_impulse);
  EXPECT_NEAR(peak_p, expected_peak_p, 0.10 * expected_peak_p);
  EXPECT_NEAR(impulse_p, expected_impulse_p, 0.10 * expected_impulse_p);
  EXPECT_NEAR(peak, expected_peak, 0.10 * expected_peak);
  EXPECT_NEAR(impulse, expected_impulse, 0.10 * expected_impulse);
  // The sphere has passed the shock: the shock stands beyond it.
  EXPECT_GT(s.us * scene.run.end_time + 0.010, 0.020 + a);
  fs::remove_all(dir);
}
