// Gas-particle coupling (paper eqs. 2-3 sources, 5-16): single-parcel relaxation against
// reference integrations, conservation of the exchange terms step by step, mass conservation,
// and the measured drift that the non-conservative alpha_g grad p and p d(alpha_g)/dt terms allow.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "solver/core/derivatives.hpp"
#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/gas/transport.hpp"
#include "solver/laws/pressure_force.hpp"
#include "solver/sim/simulation.hpp"

using namespace dustlift;

namespace {

/// A periodic-in-x box of gas with one parcel (layer of one) and the named effects.
std::string single_parcel_scene(const std::string& gas_state, const std::string& coupling) {
  return R"(
[run]
end_time = 1e-3
[grid]
x = { start = 0.0, end = 0.004, cells = 4 }
y = { start = 0.0, end = 0.004, cells = 4 }
[gas]
thermo = "calorically_perfect"
gamma = 1.4
gas_constant = 288.19
[gas.transport]
model = "gordon_wilke"
[boundary]
left = "periodic"
right = "periodic"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "uniform"
state = )" +
         gas_state + R"(
[particles]
diameter = 100e-6
density = 980.0
real_per_parcel = 1.0
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
x_min = 0.0019
x_max = 0.0021
y_min = 0.0019
y_max = 0.0021
volume_fraction = 0.19635
[coupling]
)" + coupling;
}

double run_until(Simulation& sim, double t_end) {
  while (sim.time() < t_end * (1 - 1e-14)) sim.advance(t_end - sim.time());
  return sim.time();
}

}  // namespace

TEST(Coupling, SingleParcelDragRelaxationMatchesReferenceOde) {
  // docs/gas-solver.md: frozen post-shock gas of the Ms = 1.44 shock (gamma = 1.4 row),
  // particle from rest, drag only with Parmar xi_1 and xi_2 = 1: v(100 us) = 29.3039 m/s,
  // v(500 us) = 95.8161 m/s (RK4 reference). One-way coupling keeps the gas frozen.
  const Scene scene = parse_scene(
      single_parcel_scene(
          "{ p = 227506.0, T = 384.199, u = 216.154 }",
          "two_way = false\nmagnus = false\npressure_force = false\nrotation_torque = false\n"
          "heat_transfer = false\nvolume_fraction_correction = \"none\"\n"),
      "single.toml");
  Simulation sim(scene);
  ASSERT_NE(sim.parcels(), nullptr);
  ASSERT_EQ(sim.parcels()->size(), 1u);
  run_until(sim, 100e-6);
  std::printf("v(100 us) = %.4f m/s (reference 29.3039)\n", sim.parcels()->vx[0]);
  EXPECT_NEAR(sim.parcels()->vx[0], 29.3039, 0.01 * 29.3039);
  EXPECT_NEAR(sim.parcels()->vx[0], 29.3039, 0.002 * 29.3039);  // observed: well inside 0.2 %
  run_until(sim, 500e-6);
  std::printf("v(500 us) = %.4f m/s (reference 95.8161)\n", sim.parcels()->vx[0]);
  EXPECT_NEAR(sim.parcels()->vx[0], 95.8161, 0.002 * 95.8161);
  EXPECT_NEAR(sim.parcels()->vy[0], 0.0, 1e-12);
}

TEST(Coupling, ParcelTemperatureRelaxesAsRanzMarshallOde) {
  // Gas at 400 K streams at 50 m/s past a parcel at 300 K held by no force (drag off), so Re_p
  // and Nu are constant: T(t) = T_g - (T_g - T_0) exp(-t / tau), tau = m c / (pi d lambda Nu).
  const Scene scene = parse_scene(
      single_parcel_scene("{ p = 101325.0, T = 400.0, u = 50.0 }",
                          "two_way = false\ndrag = false\nmagnus = false\npressure_force = false\n"
                          "rotation_torque = false\n"),
      "heat.toml");
  Simulation sim(scene);
  run_until(sim, 1e-3);
  const double T = sim.parcels()->temperature[0];
  // Closed form with the gas properties at 400 K (Gordon-Wilke, tested in test_gas_transport).
  const double d = 100e-6, rho = 101325.0 / (288.19 * 400.0);
  const TransportProperties tp = air_transport_gordon_wilke(400.0);
  const double mu400 = tp.mu, lam400 = tp.lambda;
  const double re = rho * 50.0 * d / mu400;
  const double cp = 1.4 / 0.4 * 288.19;
  const double pr = mu400 * cp / lam400;
  const double nu = 2.0 + 0.6 * std::sqrt(re) * std::cbrt(pr);
  const double m = 980.0 * std::numbers::pi / 6.0 * d * d * d;
  const double tau = m * 1200.0 / (std::numbers::pi * d * lam400 * nu);
  const double expected = 400.0 - 100.0 * std::exp(-1e-3 / tau);
  std::printf("T(1 ms) - 300 K = %.5f K (closed form %.5f K)\n", T - 300.0, expected - 300.0);
  EXPECT_GT(T, 300.5);
  EXPECT_NEAR(T - 300.0, expected - 300.0, 0.01 * (expected - 300.0));
}

namespace {

/// Closed box: periodic in x, slip walls at top and bottom; a loose layer of parcels that the
/// test agitates; every effect on. Wall contacts are frictionless so that the walls exchange
/// no x momentum with the parcels.
const char* kBox = R"(
[run]
end_time = 1.0
[grid]
x = { start = 0.0, end = 0.008, cells = 16 }
y = { start = 0.0, end = 0.004, cells = 8 }
[gas]
thermo = "thermally_perfect"
[boundary]
left = "periodic"
right = "periodic"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "uniform"
state = { p = 101325.0, T = 330.0, u = 15.0, v = -3.0 }
[particles]
diameter = 100e-6
density = 980.0
temperature = 300.0
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
x_min = 0.0
x_max = 0.008
y_min = 0.0
y_max = 0.002
volume_fraction = 0.35
[particles.wall_contact]
k_t = 0.0
damping = 0.0
)";

struct Totals {
  double mass, px, py, energy;
};

Totals totals(const Simulation& sim) {
  const GasTotals g = sim.gas().totals();
  Totals t{g.mass, g.momentum_x, g.momentum_y, g.energy};
  const ParcelSystem& ps = *sim.parcels();
  for (std::size_t k = 0; k < ps.size(); ++k) {
    t.mass += ps.mass[k];
    t.px += ps.mass[k] * ps.vx[k];
    t.py += ps.mass[k] * ps.vy[k];
    t.energy += 0.5 * ps.mass[k] * (ps.vx[k] * ps.vx[k] + ps.vy[k] * ps.vy[k]) +
                0.5 * ps.inertia[k] * ps.omega[k] * ps.omega[k] +
                ps.mass[k] * sim.scene().particles.heat_capacity * ps.temperature[k];
  }
  return t;
}

}  // namespace

/// The closed box with the given scene overrides: gas loss and parcel gain equal step by step
/// (to 1e-12), total mass constant, momentum and energy drift within what the model allows.
void closed_box_conserves(const std::vector<std::string>& overrides) {
  const Scene scene = parse_scene(kBox, "box.toml", overrides);
  Simulation sim(scene);
  ParcelSystem& ps = *sim.parcels();
  ASSERT_GT(ps.size(), 300u);
  // Agitate the parcels reproducibly (splitmix-like hash of the index).
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const double a = std::sin(12.9898 * static_cast<double>(k) + 1.0),
                 b = std::cos(78.233 * static_cast<double>(k));
    ps.vx[k] = 2.0 * a;
    ps.vy[k] = 2.0 * b;
    ps.omega[k] = 2000.0 * a * b;
  }
  const Totals start = totals(sim);
  double max_momentum_mismatch = 0.0, max_energy_mismatch = 0.0, impulse_scale = 0.0,
         energy_scale = 0.0;
  double sum_exchange_px = 0.0;
  for (int step = 0; step < 1000; ++step) {
    const GasTotals before = sim.gas().totals();
    (void)before;
    sim.advance(1.0);
    const ExchangeTotals e = sim.coupling()->last_exchange(*sim.parcels());
    // What the gas gives through f_p, s_p, q_p equals what the parcels receive, step by step.
    const double scale_p = std::abs(e.parcel_impulse_x) + std::abs(e.parcel_impulse_y) + 1e-300;
    const double scale_e = std::abs(e.parcel_work) + std::abs(e.parcel_heat) + 1e-300;
    max_momentum_mismatch =
        std::max({max_momentum_mismatch, std::abs(e.gas_impulse_x - e.parcel_impulse_x) / scale_p,
                  std::abs(e.gas_impulse_y - e.parcel_impulse_y) / scale_p});
    max_energy_mismatch = std::max(
        max_energy_mismatch, std::abs(e.gas_energy - (e.parcel_work + e.parcel_heat)) / scale_e);
    impulse_scale += scale_p;
    energy_scale += scale_e;
    sum_exchange_px += e.parcel_impulse_x;
  }
  const Totals end = totals(sim);
  EXPECT_LT(max_momentum_mismatch, 1e-12);
  EXPECT_LT(max_energy_mismatch, 1e-12);
  EXPECT_NEAR(end.mass, start.mass, 1e-12 * start.mass);
  // Drift allowed by the non-conservative alpha_g grad p (gas) and -V_p grad p (parcels) pair and
  // the p d(alpha_g)/dt work: measured against what was exchanged (docs/coupling.md explains).
  const double drift_px = std::abs(end.px - start.px) / impulse_scale;
  const double drift_e = std::abs(end.energy - start.energy) / energy_scale;
  std::printf("exchange mismatch: momentum %.2e, energy %.2e (relative, max over steps)\n",
              max_momentum_mismatch, max_energy_mismatch);
  std::printf(
      "drift over 1000 steps: x momentum %.3e of the exchanged impulse, energy %.3e of the "
      "exchanged energy\n",
      drift_px, drift_e);
  std::printf("exchanged: impulse %.3e N s/m, energy %.3e J/m over t = %.3e s\n", impulse_scale,
              energy_scale, sim.time());
  EXPECT_GT(impulse_scale, 0.0);
  EXPECT_LT(drift_px, 0.05);
  EXPECT_LT(drift_e, 0.05);
}

TEST(Coupling, ClosedBoxConservesMassAndExchangesExactly) {
  closed_box_conserves({});
}

TEST(Coupling, ClosedBoxConservesWithTheResolvedAddedMassAndOsnesDrag) {
  // The added-mass force is exchanged like drag: the gas loses exactly what the parcels gain.
  closed_box_conserves(
      {"coupling.added_mass=true", "coupling.volume_fraction_correction=\"osnes\""});
}

TEST(Coupling, AddedMassInAUniformlyAcceleratingGasIsCmRhoVpDuDt) {
  // A uniform gas accelerated by a body force g = 1e4 m/s^2 in a periodic box (one-way: it does
  // not feel the beads), beads floating apart with only the added mass on: each bead feels
  // F = C_M rho V_p (g - a_p) with the gas's Du/Dt = g read from the resolved flow, and so
  // accelerates at a_p = C_M rho V_p g / (m + C_M rho V_p).
  const Scene scene = parse_scene(
      kBox, "box.toml",
      {"gas.gravity=[1.0e4, 0.0]", "initial.state={ p = 101325.0, T = 300.0 }",
       "coupling.two_way=false", "coupling.drag=false", "coupling.magnus=false",
       "coupling.pressure_force=false", "coupling.rotation_torque=false",
       "coupling.heat_transfer=false", "coupling.added_mass=true",
       "coupling.added_mass_volume_fraction=\"none\"", "particles.layer.arrangement=\"hexagonal\"",
       "particles.layer.y_min=0.001", "particles.layer.y_max=0.002",
       "particles.layer.volume_fraction=0.1", "run.max_steps=60"});
  Simulation sim(scene);
  for (int step = 0; step < 60; ++step) sim.advance(1.0);
  const ParcelSystem& ps = *sim.parcels();
  const std::vector<double>& f_am = ps.column(ps.find_part(ForcePart::AddedMass, 0));
  const double rho = 101325.0 / (288.19 * 300.0), g = 1.0e4;
  const double d = scene.particles.particle_diameter, vp = std::numbers::pi / 6.0 * d * d * d;
  const double m = scene.particles.density * vp, m_a = 0.5 * rho * vp;
  // The slip Mach number stays below 0.01, where C_M = 1/2 to within 2e-4.
  const double expected = 0.5 * rho * vp * g * m / (m + m_a);
  ASSERT_GT(ps.size(), 10u);
  for (std::size_t k = 0; k < ps.size(); ++k)
    ASSERT_NEAR(f_am[k], expected, 3e-4 * expected) << "parcel " << k;
  EXPECT_GT(ps.vx[0], 0.0);
}

TEST(Coupling, SampledRotationAndPressureForceEqualFullGridDerivatives) {
  // The coupling makes the vorticity and grad p only at the cells its parcels' quads can read
  // (within one cell of a cell with alpha_p > 0). The sampled values must be those of the
  // derivatives over the whole grid, bit for bit, also for single parcels high above the layer.
  const Scene scene = parse_scene(kBox, "box.toml");
  Simulation sim(scene);
  ParcelSystem& ps = *sim.parcels();
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const double a = std::sin(12.9898 * static_cast<double>(k) + 1.0),
                 b = std::cos(78.233 * static_cast<double>(k));
    ps.vx[k] = 2.0 * a;
    ps.vy[k] = 2.0 * b;
    ps.omega[k] = 2000.0 * a * b;
  }
  // Four lone parcels in the upper rows (the layer fills y < 2 mm of the 4 mm box).
  for (std::size_t q = 0; q < 4; ++q) {
    const std::size_t k = q * (ps.size() / 4);
    ps.x[k] = 0.0011 + 0.0019 * static_cast<double>(q);
    ps.y[k] = 0.0027 + 0.0003 * static_cast<double>(q);
  }
  sim.advance(1.0);  // the deposit is now at the parcels' positions, as in any step
  const GasPrimitives g = sim.gas().primitives();
  const Grid2D& grid = sim.grid();
  Field2D vorticity(grid), dpdx(grid), dpdy(grid);
  vorticity_z_rows(grid, *g.u, *g.v, 0, grid.ny(), vorticity);
  gradient_rows(grid, *g.p, 0, grid.ny(), dpdx, dpdy);
  for (Field2D* f :
       {&vorticity, &dpdx, &dpdy}) {  // edge values into the ghosts, as the coupling does
    for (int j = 0; j < grid.ny(); ++j) {
      (*f)(-1, j) = (*f)(0, j);
      (*f)(grid.nx(), j) = (*f)(grid.nx() - 1, j);
    }
    for (int i = -1; i <= grid.nx(); ++i) {
      (*f)(i, -1) = (*f)(i, 0);
      (*f)(i, grid.ny()) = (*f)(i, grid.ny() - 1);
    }
  }
  std::map<std::int64_t, std::pair<double, double>> position_by_id;
  for (std::size_t k = 0; k < ps.size(); ++k) position_by_id[ps.id[k]] = {ps.x[k], ps.y[k]};
  double highest = 0.0;
  for (std::size_t k = 0; k < ps.size(); ++k) highest = std::max(highest, ps.y[k]);
  ASSERT_GT(highest, 0.0027);
  sim.advance(1.0);  // samples the gas above at the positions above
  const std::vector<double>* rotation = nullptr;
  for (std::size_t c = 0; c < ps.attached_count(); ++c) {
    if (ps.attached_spec(c).name == "gas_rotation") rotation = &ps.attached(c);
  }
  ASSERT_NE(rotation, nullptr);
  const double d = scene.particles.particle_diameter;
  const std::vector<double>& pressure_fx = ps.column(ps.find_part(ForcePart::Pressure, 0));
  const std::vector<double>& pressure_fy = ps.column(ps.find_part(ForcePart::Pressure, 1));
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const auto [x, y] = position_by_id.at(ps.id[k]);
    const InterpolationStencil st = interpolation_stencil(grid, x, y);
    const Vec2 force = aero::pressure_force(d, {st.apply(dpdx), st.apply(dpdy)});
    if ((*rotation)[k] != 0.5 * st.apply(vorticity) || pressure_fx[k] != force.x ||
        pressure_fy[k] != force.y) {
      ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0u) << "of " << ps.size() << " parcels";
}

TEST(Coupling, QuiescentGasOverRestingLayerStaysAtRest) {
  // Uniform pressure, gas at rest, a resting layer making alpha_g jump: nothing may move.
  const Scene scene = parse_scene(kBox, "box.toml", {"initial.state={ p = 101325.0, T = 300.0 }"});
  Simulation sim(scene);
  for (int step = 0; step < 50; ++step) sim.advance(1.0);
  const GasPrimitives g = sim.gas().primitives();
  double umax = 0.0;
  for (int j = 0; j < sim.grid().ny(); ++j)
    for (int i = 0; i < sim.grid().nx(); ++i)
      umax = std::max({umax, std::abs((*g.u)(i, j)), std::abs((*g.v)(i, j))});
  double vmax = 0.0;
  const ParcelSystem& ps = *sim.parcels();
  for (std::size_t k = 0; k < ps.size(); ++k)
    vmax = std::max({vmax, std::abs(ps.vx[k]), std::abs(ps.vy[k])});
  EXPECT_LT(umax, 1e-9);
  EXPECT_LT(vmax, 1e-9);
}

TEST(Coupling, GasOnlySceneBuildsNoParcelCode) {
  const Scene scene = parse_scene(kBox, "box.toml", {"particles={ enabled = false }"});
  Simulation sim(scene);
  EXPECT_EQ(sim.parcels(), nullptr);
  EXPECT_EQ(sim.coupling(), nullptr);
  EXPECT_EQ(sim.view().parcels, nullptr);
}
