// The inviscid-unsteady (added-mass) force of Parmar, Haselbacher & Balachandar (2008): its
// coefficient, the gas's momentum rate the effect takes from the resolved flow (a gas that
// accelerates uniformly, a steady gas whose pressure gradient the drag balances), the implicit
// virtual mass that keeps a dense cloud stable, Ling et al.'s -grad p form, and the implicit
// sub-step against the exact motion of a sphere in a uniformly accelerating inviscid fluid.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/added_mass.hpp"
#include "solver/coupling/effects/effect_list.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/added_mass.hpp"
#include "tests/unit/forcing_fixture.hpp"

using namespace dustlift;

namespace {

constexpr double kPi = std::numbers::pi;
using aero::AddedMassVolumeFraction;
using forcing_fixture::column;

TEST(AddedMass, CoefficientIsParmarsMachFitTimesTheVolumeFractionFactor) {
  // Incompressible sphere: C_M = 1/2.
  EXPECT_DOUBLE_EQ(aero::added_mass_coefficient(0.0, 0.0, AddedMassVolumeFraction::Beguin), 0.5);
  // Parmar et al. (2008): 1/2 (1 + 1.8 M^2 + 7.6 M^4) at M = 0.4: 1/2 (1 + 0.288 + 0.19456).
  EXPECT_NEAR(aero::added_mass_coefficient(0.4, 0.0, AddedMassVolumeFraction::None), 0.5 * 1.48256,
              1e-15);
  // Held beyond M = 0.6 (the fit's range): 1/2 x 2.63296.
  EXPECT_NEAR(aero::added_mass_coefficient(0.6, 0.0, AddedMassVolumeFraction::None), 0.5 * 2.63296,
              1e-12);
  EXPECT_EQ(aero::added_mass_coefficient(1.3, 0.0, AddedMassVolumeFraction::None),
            aero::added_mass_coefficient(0.6, 0.0, AddedMassVolumeFraction::None));
  // Beguin et al. (2016): 1 + 0.68 phi^2; Zuber (1964): (1 + 2 phi) / (1 - phi). At the
  // curtain's phi = 0.21: 1.029988 against 1.797.
  EXPECT_NEAR(aero::added_mass_coefficient(0.0, 0.21, AddedMassVolumeFraction::Beguin),
              0.5 * 1.029988, 1e-15);
  EXPECT_NEAR(aero::added_mass_coefficient(0.0, 0.21, AddedMassVolumeFraction::Zuber),
              0.5 * 1.42 / 0.79, 1e-15);
  EXPECT_EQ(aero::added_mass_coefficient(0.0, 0.21, AddedMassVolumeFraction::None), 0.5);
}

/// One parcel's added-mass columns after the effect has sampled it (at times t, in order).
struct OneParcel {
  ParcelSystem table{[] {
    DemConfig c;
    c.enabled = true;
    return c;
  }()};
  AddedMassEffect effect;
  explicit OneParcel(const CouplingConfig& c) : effect(c) {
    table.add_parcel(ParcelInit{});
    effect.attach(table);
  }
  void sample(const ModelInput& in, double t) {
    effect.coefficients(&in, 0, 1, table, StepContext{t});
  }
  Vec2 fluid_part() {
    return {column(table, "added_mass_gas_x"), column(table, "added_mass_gas_y")};
  }
};

CouplingConfig added_mass(AddedMassVolumeFraction v, aero::FluidAcceleration a, bool two_way) {
  CouplingConfig c = forcing_fixture::no_effects();
  c.added_mass = true;
  c.added_mass_volume_fraction = v;
  c.added_mass_fluid_acceleration = a;
  c.two_way = two_way;
  return c;
}

ModelInput sample_at(double rho, double u, double v, double alpha_g, double dpdx, double dpdy) {
  ModelInput in;
  in.gas.rho = rho;
  in.gas.u = u;
  in.gas.v = v;
  in.gas.c = 400.0;
  in.gas.alpha_g = alpha_g;
  in.gas.dpdx = dpdx;
  in.gas.dpdy = dpdy;
  in.gas.rho_u = rho * u;
  in.gas.rho_v = rho * v;
  const double d = 115e-6;
  in.parcel = ParcelAtSample{0.0, 0.0, 0.0, d, 2520.0 * kPi / 6.0 * d * d * d};
  in.slip = std::hypot(u, v);
  return in;
}

TEST(AddedMass, AUniformlyAcceleratingGasGivesCmRhoVpDuDt) {
  // The gas speeds up at a = 2e5 m/s^2, uniformly (grad(rho u) = 0): D(rho u)/Dt = rho a, read
  // from the rate of the sampled rho u along the parcel's path. One-way: the gas does not feel
  // the particle.
  OneParcel p(added_mass(AddedMassVolumeFraction::None, aero::FluidAcceleration::Resolved, false));
  const double rho = 2.07, a = 2.0e5, dt = 2.5e-7;
  p.sample(sample_at(rho, 10.0, 0.0, 1.0, 0.0, 0.0), 1e-5);
  EXPECT_EQ(p.fluid_part().x, 0.0) << "no rate before the second sample";
  const ModelInput second = sample_at(rho, 10.0 + a * dt, 0.0, 1.0, 0.0, 0.0);
  p.sample(second, 1e-5 + dt);
  const double c_m =
      aero::added_mass_coefficient(second.slip / 400.0, 0.0, AddedMassVolumeFraction::None);
  const double vp = kPi / 6.0 * std::pow(115e-6, 3);
  EXPECT_NEAR(p.fluid_part().x, c_m * rho * vp * a, 1e-9 * c_m * rho * vp * a);
  EXPECT_EQ(p.fluid_part().y, 0.0);
  // The force at the parcel's own acceleration a_p is C_M rho V_p (a - a_p) (Parmar et al.).
  const double a_p = 3.0e4;
  const Vec2 f =
      aero::added_mass_force_at(p.fluid_part(), column(p.table, "added_mass"), {a_p, 0.0});
  EXPECT_NEAR(f.x, c_m * rho * vp * (a - a_p), 1e-9 * c_m * rho * vp * a);
}

TEST(AddedMass, ASteadyGasWhosePressureGradientDragBalancesGivesNothing) {
  // Gas through a fixed bed: steady, uniform momentum (the pressure gradient is balanced by the
  // drag, not by acceleration). The resolved rate is zero to the last bit, however dense the
  // cell and whatever the gradient; -grad p, Ling et al.'s form, is not.
  for (const double alpha_g : {1.0, 0.79, 0.41}) {
    OneParcel p(
        added_mass(AddedMassVolumeFraction::Beguin, aero::FluidAcceleration::Resolved, true));
    const ModelInput steady = sample_at(2.07, 40.0, -3.0, alpha_g, -3.0e7, 2.0e6);
    for (int step = 0; step < 5; ++step) p.sample(steady, 1e-6 * step);
    EXPECT_EQ(p.fluid_part().x, 0.0) << alpha_g;
    EXPECT_EQ(p.fluid_part().y, 0.0) << alpha_g;
    OneParcel ling(added_mass(AddedMassVolumeFraction::Beguin,
                              aero::FluidAcceleration::PressureGradient, true));
    ling.sample(steady, 0.0);
    EXPECT_GT(ling.fluid_part().x, 0.0) << "-C_M V_p grad p";
  }
}

TEST(AddedMass, TheConvectiveRateFollowsTheGasNotTheParcel) {
  // A steady gas whose momentum varies in space: along a parcel at rest the sampled rho u does
  // not change, but the gas carries its momentum past it: D(rho u)/Dt = u . grad(rho u).
  OneParcel p(added_mass(AddedMassVolumeFraction::None, aero::FluidAcceleration::Resolved, false));
  ModelInput in = sample_at(1.5, 200.0, 0.0, 1.0, 0.0, 0.0);
  in.gas.dx_rho_u = 4.0e3;  // kg/(m^3 s) per m
  in.gas.dy_rho_v = -1.0e3;
  p.sample(in, 0.0);
  p.sample(in, 1e-6);
  const double c_m =
      aero::added_mass_coefficient(in.slip / 400.0, 0.0, AddedMassVolumeFraction::None);
  const double vp = kPi / 6.0 * std::pow(115e-6, 3);
  EXPECT_NEAR(p.fluid_part().x, c_m * vp * 200.0 * 4.0e3, 1e-12 * c_m * vp * 8e5);
  EXPECT_EQ(p.fluid_part().y, 0.0);  // v = 0: no transport of rho v's gradient along y
}

TEST(AddedMass, ImplicitVirtualMassKeepsADenseCloudStable) {
  // A packed cell (alpha_g = 0.41) under a slip of Mach 0.55: alpha_p C_M / alpha_g = 2.0, so a
  // lagged explicit reaction (the gas shows last step's reaction, the parcels answer it) grows
  // by -2.0 a step. The gas model: it would accelerate at A_ext without the cloud; the cloud's
  // reaction takes alpha_p C_M (A - 0) / alpha_g off it (parcels at rest).
  const double alpha_g = 0.41, rho = 2.0, a_ext = 5.0e6;
  const ModelInput base = sample_at(rho, 0.0, 0.0, alpha_g, 0.0, 0.0);
  ModelInput in = base;
  in.slip = 0.55 * 400.0;
  const double c_m =
      aero::added_mass_coefficient(0.55, 1.0 - alpha_g, AddedMassVolumeFraction::Beguin);
  const double g = (1.0 - alpha_g) * c_m / alpha_g;
  ASSERT_GT(g, 1.9);
  OneParcel p(added_mass(AddedMassVolumeFraction::Beguin, aero::FluidAcceleration::Resolved, true));
  const double vp = kPi / 6.0 * std::pow(115e-6, 3), dt = 1e-7;
  double rho_u = 0.0, used = 0.0;
  for (int step = 0; step < 40; ++step) {
    in.gas.u = rho_u / rho;
    in.gas.rho_u = rho_u;
    p.sample(in, dt * step);
    used = p.fluid_part().x / (c_m * vp);  // the rate the parcels take
    // The gas over the step: its own acceleration less the cloud's reaction.
    rho_u += dt * (a_ext * rho - g * used);
  }
  // The fixed point of the coupled pair: A = rho a_ext / (1 + g); reached, and never oscillating.
  EXPECT_NEAR(used, rho * a_ext / (1.0 + g), 1e-9 * rho * a_ext);
}

/// One parcel at rest in a frozen uniform pressure gradient, no drag: with the pressure force
/// and the added mass (-grad p form), (m + m_a) dv/dt = -V_p (1 + C_M) grad p exactly (a sphere
/// in an accelerating inviscid fluid), whatever the sub-steps.
TEST(AddedMass, ImplicitSubstepsGiveTheExactAccelerationInAUniformGradient) {
  DemConfig cfg;
  cfg.domain.x_min = cfg.domain.y_min = 0.0;
  cfg.domain.x_max = cfg.domain.y_max = 1.0;
  cfg.domain.wall_bottom = false;
  cfg.particle_diameter = cfg.parcel_diameter = 115e-6;
  cfg.density = 2520.0;
  ParcelSystem ps(cfg);
  const double d = 115e-6, rho_p = 2520.0, rho_g = 2.07, grad_p = -3.0e7, c_m = 0.5;
  ParcelInit init;
  init.x = init.y = 0.5;
  init.diameter = init.real_diameter = d;
  init.density = rho_p;
  ps.add_parcel(init);
  CouplingConfig c = forcing_fixture::no_effects();
  c.pressure_force = c.added_mass = true;
  forcing_fixture::Forcing f(ps, c);
  const double vp = kPi / 6.0 * d * d * d, m = rho_p * vp, m_a = c_m * rho_g * vp;
  column(ps, "pressure_fx") = -vp * grad_p;
  column(ps, "added_mass") = m_a;
  column(ps, "added_mass_gas_x") = -c_m * vp * grad_p;
  column(ps, "inv_total_mass") = 1.0 / (m + m_a);
  const double t = 2e-6;
  ps.advance(t);
  const double a_exact = -vp * (1.0 + c_m) * grad_p / (m + m_a);
  EXPECT_NEAR(ps.vx[0], a_exact * t, 1e-12 * a_exact * t);
  // The added-mass force stored is F_g - m_a a, and the impulse exchanged is its integral.
  const double f_am = -c_m * vp * grad_p - m_a * a_exact;
  EXPECT_NEAR(column(ps, "added_mass_fx"), f_am, 1e-12 * std::abs(f_am));
  EXPECT_NEAR(column(ps, "impulse_x"), f_am * t, 1e-12 * std::abs(f_am * t));
  // A neutrally buoyant sphere (rho_p = rho_g) would follow the fluid: -grad p / rho.
  EXPECT_GT(std::abs(a_exact), std::abs(-vp * grad_p / m));
}

TEST(AddedMass, IsListedWithItsChoicesWhenOn) {
  CouplingConfig c;
  c.added_mass = true;
  const CouplingEffects effects(c);
  EXPECT_TRUE(effects.reads().momentum_gradient);
  std::string all;
  for (const auto& d : effects.descriptions()) all += d + "\n";
  EXPECT_NE(all.find("Beguin"), std::string::npos) << all;
  EXPECT_NE(all.find("resolved"), std::string::npos) << all;
  CouplingConfig ling = c;
  ling.added_mass_fluid_acceleration = aero::FluidAcceleration::PressureGradient;
  EXPECT_TRUE(CouplingEffects(ling).reads().pressure_gradient);
  EXPECT_FALSE(CouplingEffects(ling).reads().momentum_gradient);
  std::string paper_list;
  for (const auto& d : CouplingEffects(CouplingConfig{}).descriptions()) paper_list += d + "\n";
  EXPECT_EQ(paper_list.find("added mass"), std::string::npos) << "off by default";
}

}  // namespace
