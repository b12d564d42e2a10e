// The coupling's effects (solver/coupling/effects/): each effect's per-parcel coefficient, as
// the coupling computes it once per CFD step, times its sub-step piece, as the DEM's forced
// Euler step applies it, is the published law (aero::, solver/laws/) at the sampled state; the
// DEM stores exactly the sub-step pieces; and the effect list alone decides what is read and
// which columns exist.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/drag.hpp"
#include "solver/coupling/effects/effect_list.hpp"
#include "solver/coupling/effects/heat_transfer.hpp"
#include "solver/coupling/effects/magnus.hpp"
#include "solver/coupling/effects/pressure_force.hpp"
#include "solver/coupling/effects/rotation_torque.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/drag.hpp"
#include "solver/laws/heat_transfer.hpp"
#include "solver/laws/magnus.hpp"
#include "solver/laws/pressure_force.hpp"
#include "solver/laws/rotation_torque.hpp"
#include "tests/unit/forcing_fixture.hpp"

using namespace dustlift;

namespace {

/// Post-shock air over a lagging, spinning 100 um particle (Re ~ 1500, M_p ~ 0.5).
ModelInput post_shock_parcel() {
  ModelInput in;
  in.gas = GasSample{.rho = 2.05,
                     .u = 216.0,
                     .v = -12.0,
                     .p = 2.2e5,
                     .T = 380.0,
                     .mu = 2.23e-5,
                     .lambda = 0.0318,
                     .c = 393.0,
                     .cp = 1012.0,
                     .alpha_g = 0.62,
                     .vorticity = -3.1e4,
                     .dpdx = -4.0e7,
                     .dpdy = 1.5e6};
  const GasSample& g = in.gas;
  in.parcel = ParcelAtSample{35.0, 4.0, 900.0, 100e-6};
  const Vec2 u_r{g.u - in.parcel.vx, g.v - in.parcel.vy};
  in.slip = u_r.norm();
  in.re = g.rho * in.slip * in.parcel.diameter / g.mu;
  return in;
}

Vec2 slip_of(const ModelInput& in) {
  return {in.gas.u - in.parcel.vx, in.gas.v - in.parcel.vy};
}

/// The value an effect writes into its column `column` for one parcel sampled as `in`,
/// through the coupling's batch interface.
double coefficient_of(CouplingEffect& e, const ModelInput& in, const char* column) {
  DemConfig cfg;
  cfg.enabled = true;
  cfg.domain = DemDomain{-0.01, 0.01, -0.01, 0.01, false, false, false, false, false};
  ParcelSystem s(cfg);
  s.add_parcel(ParcelInit{});
  e.attach(s);
  e.coefficients(&in, 0, 1, s, StepContext{});
  return forcing_fixture::column(s, column);
}

double relative_difference(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

}  // namespace

TEST(CouplingEffects, DragCoefficientTimesSubstepForceIsTheDragLaw) {
  CouplingConfig c;
  c.volume_fraction = {aero::VolumeFractionCorrection::Kind::Sangani, 0.5};
  DragEffect effect(c);
  const ModelInput in = post_shock_parcel();
  const double K = coefficient_of(effect, in, "drag_coefficient");
  EXPECT_EQ(coefficient_of(effect, in, "drag_coefficient_sampled"), K);
  const aero::GasAtParcel g{in.gas.rho, {in.gas.u, in.gas.v}, in.gas.mu, in.gas.c, in.gas.alpha_g};
  const Vec2 law =
      aero::drag_force(g, {in.parcel.vx, in.parcel.vy}, in.parcel.diameter, c.volume_fraction);
  const Vec2 substep = aero::linear_drag(K, slip_of(in));
  EXPECT_EQ(substep.x, law.x);
  EXPECT_EQ(substep.y, law.y);
  EXPECT_GT(substep.x, 0.0);  // along the slip
}

TEST(CouplingEffects, MagnusCoefficientTimesSubstepForceIsTheLiftLawInBothConventions) {
  for (const auto conv : {aero::MagnusConvention::Paper, aero::MagnusConvention::Standard}) {
    CouplingConfig c;
    c.magnus_coefficient = 0.8;
    c.lun_liu = true;
    c.magnus_convention = conv;
    MagnusEffect effect(c);
    const ModelInput in = post_shock_parcel();
    const double M = coefficient_of(effect, in, "magnus_coefficient");
    const double w_r = aero::relative_rotation(in.gas.vorticity, in.parcel.omega);
    const Vec2 law = aero::magnus_force(in.gas.rho, in.parcel.diameter, slip_of(in), w_r,
                                        0.8 * aero::lun_liu_factor(in.re), conv);
    const Vec2 substep = aero::magnus_lift(M, w_r, slip_of(in));
    EXPECT_EQ(substep.x, law.x);
    EXPECT_EQ(substep.y, law.y);
    // The convention's sign is the coefficient's: the paper's is the standard one reversed.
    EXPECT_EQ(M < 0.0, conv == aero::MagnusConvention::Paper);
  }
}

TEST(CouplingEffects, PressureCoefficientIsTheSampledForce) {
  PressureForceEffect effect;
  const ModelInput in = post_shock_parcel();
  const Vec2 law = aero::pressure_force(in.parcel.diameter, {in.gas.dpdx, in.gas.dpdy});
  EXPECT_EQ(coefficient_of(effect, in, "pressure_fx"), law.x);
  EXPECT_EQ(coefficient_of(effect, in, "pressure_fy"), law.y);
}

TEST(CouplingEffects, TorqueSlopeTimesTheStepsRelativeRotationIsTheFrictionTorque) {
  for (const double stokes_below : {0.0, 7.93, 1e9}) {
    CouplingConfig c;
    c.torque_stokes_below = stokes_below;
    RotationTorqueEffect effect(c);
    const ModelInput in = post_shock_parcel();
    const double kappa = coefficient_of(effect, in, "torque_coefficient");
    const double w0 = aero::relative_rotation(in.gas.vorticity, in.parcel.omega);
    const double law =
        aero::rotation_torque(in.gas.rho, in.gas.mu, in.parcel.diameter, w0, stokes_below);
    // kappa = M(w0) / w0: back at w0 within the rounding of one division and one product.
    EXPECT_LE(relative_difference(aero::linear_torque(kappa, w0), law),
              4 * std::numeric_limits<double>::epsilon())
        << stokes_below;
  }
  // At zero relative rotation the slope is Stokes' pi mu d^3, the fit's small-Re_w limit.
  CouplingConfig c;
  RotationTorqueEffect effect(c);
  ModelInput in = post_shock_parcel();
  in.parcel.omega = 0.5 * in.gas.vorticity;
  const double kappa = coefficient_of(effect, in, "torque_coefficient");
  EXPECT_EQ(kappa, aero::stokes_torque_slope(in.gas.mu, in.parcel.diameter));
  EXPECT_EQ(aero::rotation_torque(in.gas.rho, in.gas.mu, in.parcel.diameter, 2.0, 1e9),
            aero::stokes_torque_slope(in.gas.mu, in.parcel.diameter) * 2.0);
}

TEST(CouplingEffects, HeatCoefficientTimesTheTemperatureDifferenceIsRanzMarshall) {
  HeatTransferEffect effect;
  const ModelInput in = post_shock_parcel();
  const double H = coefficient_of(effect, in, "heat_coefficient");
  const double pr = in.gas.mu * in.gas.cp / in.gas.lambda;
  const double nu = aero::nusselt_ranz_marshall(in.re, pr);
  const double T_p = 300.0, d = in.parcel.diameter;
  const double q = aero::linear_heat_flow(H, in.gas.T, T_p);
  EXPECT_EQ(q, aero::heat_flow(in.gas.lambda, nu, d, in.gas.T, T_p));
  // The law as eqs. (8)-(9) print it: pi d^2 (Nu lambda / d) (T_g - T_p).
  const double printed = std::acos(-1.0) * d * d * (nu * in.gas.lambda / d) * (in.gas.T - T_p);
  EXPECT_LE(relative_difference(q, printed), 4 * std::numeric_limits<double>::epsilon());
}

TEST(CouplingEffects, TheListDecidesWhatIsReadAndWhichColumnsExist) {
  const auto columns_of = [](const CouplingConfig& c) {
    DemConfig cfg;
    cfg.enabled = true;
    ParcelSystem s(cfg);
    CouplingEffects effects(c);
    effects.attach(s);
    std::vector<std::string> names;
    for (std::size_t k = 0; k < s.attached_count(); ++k) names.push_back(s.attached_spec(k).name);
    return names;
  };
  const CouplingConfig all;
  const CouplingEffects every(all);
  EXPECT_TRUE(every.reads().rotation);
  EXPECT_TRUE(every.reads().pressure_gradient);
  EXPECT_EQ(every.descriptions().size(), 5u);
  const std::vector<std::string> every_column = columns_of(all);
  for (const char* part : {"drag_fx", "magnus_fy", "pressure_fx", "fluid_torque", "heat_rate"})
    EXPECT_NE(std::find(every_column.begin(), every_column.end(), part), every_column.end())
        << part;

  // The gas rotation is read by the Magnus lift and the torque only, grad p by the pressure
  // force only: without them no vorticity or gradient field is made, and their columns do not
  // exist.
  CouplingConfig c;
  c.magnus = false;
  c.rotation_torque = false;
  c.pressure_force = false;
  const CouplingEffects some(c);
  EXPECT_FALSE(some.reads().rotation);
  EXPECT_FALSE(some.reads().pressure_gradient);
  EXPECT_EQ(some.descriptions().size(), 2u);
  const std::vector<std::string> some_columns = columns_of(c);
  for (const char* absent : {"magnus_fx", "pressure_fx", "fluid_torque", "torque_coefficient"})
    EXPECT_EQ(std::find(some_columns.begin(), some_columns.end(), absent), some_columns.end())
        << absent;
  c.rotation_torque = true;
  EXPECT_TRUE(CouplingEffects(c).reads().rotation);

  const CouplingEffects empty(forcing_fixture::no_effects());
  EXPECT_TRUE(empty.empty());
  EXPECT_TRUE(empty.descriptions().empty());
  EXPECT_TRUE(columns_of(forcing_fixture::no_effects()).empty());
}

TEST(CouplingEffects, EveryUnitOfTheBuildIsMadeWhenOnInTable1sOrder) {
  // The build lists every effect unit (effect_units.hpp); the list makes each one whose key is
  // on, ordered by its kPosition: drag, Magnus, pressure, added mass, torque, heat (Table 1's
  // order, which is also the order the sub-step adds the forces in).
  CouplingConfig c;
  c.added_mass = true;
  const std::vector<std::string> d = CouplingEffects(c).descriptions();
  const std::vector<std::string> starts{"drag:",
                                        "Magnus lift",
                                        "pressure-gradient force",
                                        "added mass",
                                        "rotational friction torque",
                                        "heat transfer"};
  ASSERT_EQ(d.size(), starts.size());
  for (std::size_t k = 0; k < d.size(); ++k) EXPECT_EQ(d[k].rfind(starts[k], 0), 0u) << d[k];
  c.magnus = false;
  c.heat_transfer = false;
  const std::vector<std::string> some = CouplingEffects(c).descriptions();
  ASSERT_EQ(some.size(), 4u);
  EXPECT_EQ(some[1].rfind("pressure-gradient force", 0), 0u) << some[1];
  EXPECT_EQ(some[3].rfind("rotational friction torque", 0), 0u) << some[3];
}

TEST(CouplingEffects, TheDemSubstepAppliesTheEffectsSubstepLaws) {
  // One forced sub-step of a single parcel: the force parts it stores are the effects'
  // sub-step pieces at the parcel's state when the sub-step began.
  DemConfig cfg;
  cfg.enabled = true;
  cfg.domain = DemDomain{-0.01, 0.01, -0.01, 0.01, false, false, false, false, false};
  ParcelSystem s(cfg);
  ParcelInit p;
  p.vx = 3.0;
  p.vy = -1.0;
  p.omega = 250.0;
  p.temperature = 320.0;
  s.add_parcel(p);
  CouplingConfig c = forcing_fixture::no_effects();
  c.drag = c.magnus = c.rotation_torque = c.heat_transfer = true;
  forcing_fixture::Forcing f(s, c);
  using forcing_fixture::column;
  const double ug = 150.0, vg = 20.0, rot = -4000.0, Tg = 900.0;
  const double K = 3.1e-7, M = -2.4e-13, kappa = 4.0e-17, H = 2.0e-6;
  column(s, "gas_u") = ug;
  column(s, "gas_v") = vg;
  column(s, "gas_rotation") = rot;
  column(s, "gas_temperature") = Tg;
  column(s, "drag_coefficient") = K;
  column(s, "magnus_coefficient") = M;
  column(s, "torque_coefficient") = kappa;
  column(s, "heat_coefficient") = H;
  s.step(s.stable_time_step());
  const Vec2 u_r{ug - p.vx, vg - p.vy};
  const double w_r = rot - p.omega;
  const Vec2 drag = aero::linear_drag(K, u_r), lift = aero::magnus_lift(M, w_r, u_r);
  EXPECT_EQ(column(s, "drag_fx"), drag.x);
  EXPECT_EQ(column(s, "drag_fy"), drag.y);
  EXPECT_EQ(column(s, "magnus_fx"), lift.x);
  EXPECT_EQ(column(s, "magnus_fy"), lift.y);
  EXPECT_EQ(column(s, "fluid_torque"), aero::linear_torque(kappa, w_r));
  EXPECT_EQ(column(s, "heat_rate"), aero::linear_heat_flow(H, Tg, p.temperature));
  EXPECT_EQ(column(s, "relative_rotation"), w_r);
}
