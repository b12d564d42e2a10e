// The coupling models (solver/coupling/models/): each model's per-parcel coefficient, as the
// coupling computes it once per CFD step, times its sub-step piece, as the DEM's forced kernel
// applies it, is the published law (aero::) at the sampled state; the DEM stores exactly the
// sub-step pieces; and the model list alone decides what is read and written.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "solver/coupling/coupling_models.hpp"
#include "solver/coupling/models/drag.hpp"
#include "solver/coupling/models/heat_transfer.hpp"
#include "solver/coupling/models/magnus.hpp"
#include "solver/coupling/models/pressure_force.hpp"
#include "solver/coupling/models/rotation_torque.hpp"
#include "solver/dem/parcel_system.hpp"

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

/// The coefficients a model computes through the coupling's batch interface.
SubstepCoefficients coefficients_of(const CouplingModel& m, const ModelInput& in) {
  SubstepCoefficients out;
  m.coefficients(&in, &out, 1);
  return out;
}

double relative_difference(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

}  // namespace

TEST(CouplingModels, DragCoefficientTimesSubstepForceIsTheDragLaw) {
  CouplingConfig c;
  c.volume_fraction = {aero::VolumeFractionCorrection::Kind::Sangani, 0.5};
  const DragModel model(c);
  const ModelInput in = post_shock_parcel();
  const double K = coefficients_of(model, in).drag;
  const aero::GasAtParcel g{in.gas.rho, {in.gas.u, in.gas.v}, in.gas.mu, in.gas.c, in.gas.alpha_g};
  const Vec2 law =
      aero::drag_force(g, {in.parcel.vx, in.parcel.vy}, in.parcel.diameter, c.volume_fraction);
  const Vec2 substep = DragModel::force(K, slip_of(in));
  EXPECT_EQ(substep.x, law.x);
  EXPECT_EQ(substep.y, law.y);
  EXPECT_GT(substep.x, 0.0);  // along the slip
}

TEST(CouplingModels, MagnusCoefficientTimesSubstepForceIsTheLiftLawInBothConventions) {
  for (const auto conv : {aero::MagnusConvention::Paper, aero::MagnusConvention::Standard}) {
    CouplingConfig c;
    c.magnus_coefficient = 0.8;
    c.lun_liu = true;
    c.magnus_convention = conv;
    const MagnusModel model(c);
    const ModelInput in = post_shock_parcel();
    const double M = coefficients_of(model, in).magnus;
    const double w_r = aero::relative_rotation(in.gas.vorticity, in.parcel.omega);
    const Vec2 law = aero::magnus_force(in.gas.rho, in.parcel.diameter, slip_of(in), w_r,
                                        0.8 * aero::lun_liu_factor(in.re), conv);
    const Vec2 substep = MagnusModel::force(M, w_r, slip_of(in));
    EXPECT_EQ(substep.x, law.x);
    EXPECT_EQ(substep.y, law.y);
    // The convention's sign is the coefficient's: the paper's is the standard one reversed.
    EXPECT_EQ(M < 0.0, conv == aero::MagnusConvention::Paper);
  }
}

TEST(CouplingModels, PressureCoefficientIsTheSampledForce) {
  const PressureForceModel model;
  const ModelInput in = post_shock_parcel();
  const SubstepCoefficients out = coefficients_of(model, in);
  const Vec2 law = aero::pressure_force(in.parcel.diameter, {in.gas.dpdx, in.gas.dpdy});
  EXPECT_EQ(out.pressure_fx, law.x);
  EXPECT_EQ(out.pressure_fy, law.y);
}

TEST(CouplingModels, TorqueSlopeTimesTheStepsRelativeRotationIsTheFrictionTorque) {
  for (const double stokes_below : {0.0, 7.93, 1e9}) {
    CouplingConfig c;
    c.torque_stokes_below = stokes_below;
    const RotationTorqueModel model(c);
    const ModelInput in = post_shock_parcel();
    const double kappa = coefficients_of(model, in).torque;
    const double w0 = aero::relative_rotation(in.gas.vorticity, in.parcel.omega);
    const double law =
        aero::rotation_torque(in.gas.rho, in.gas.mu, in.parcel.diameter, w0, stokes_below);
    // kappa = M(w0) / w0: back at w0 within the rounding of one division and one product.
    EXPECT_LE(relative_difference(RotationTorqueModel::torque(kappa, w0), law),
              4 * std::numeric_limits<double>::epsilon())
        << stokes_below;
  }
  // At zero relative rotation the slope is Stokes' pi mu d^3, the fit's small-Re_w limit.
  CouplingConfig c;
  const RotationTorqueModel model(c);
  ModelInput in = post_shock_parcel();
  in.parcel.omega = 0.5 * in.gas.vorticity;
  const double kappa = coefficients_of(model, in).torque;
  EXPECT_EQ(kappa, aero::stokes_torque_slope(in.gas.mu, in.parcel.diameter));
  EXPECT_EQ(aero::rotation_torque(in.gas.rho, in.gas.mu, in.parcel.diameter, 2.0, 1e9),
            aero::stokes_torque_slope(in.gas.mu, in.parcel.diameter) * 2.0);
}

TEST(CouplingModels, HeatCoefficientTimesTheTemperatureDifferenceIsRanzMarshall) {
  const HeatTransferModel model;
  const ModelInput in = post_shock_parcel();
  const double H = coefficients_of(model, in).heat;
  const double pr = in.gas.mu * in.gas.cp / in.gas.lambda;
  const double nu = aero::nusselt_ranz_marshall(in.re, pr);
  const double T_p = 300.0, d = in.parcel.diameter;
  const double q = HeatTransferModel::heat_flow(H, in.gas.T, T_p);
  EXPECT_EQ(q, aero::heat_flow(in.gas.lambda, nu, d, in.gas.T, T_p));
  // The law as eqs. (8)-(9) print it: pi d^2 (Nu lambda / d) (T_g - T_p).
  const double printed = std::acos(-1.0) * d * d * (nu * in.gas.lambda / d) * (in.gas.T - T_p);
  EXPECT_LE(relative_difference(q, printed), 4 * std::numeric_limits<double>::epsilon());
}

TEST(CouplingModels, TheListDecidesWhatIsReadAndWritten) {
  const CouplingConfig all;
  const CouplingModels every(all);
  EXPECT_TRUE(every.reads().rotation);
  EXPECT_TRUE(every.reads().pressure_gradient);
  EXPECT_TRUE(every.reads().temperature);
  const ForceParts w = every.writes();
  EXPECT_TRUE(w.drag && w.magnus && w.pressure && w.torque && w.heat);
  EXPECT_EQ(every.descriptions().size(), 5u);

  // The gas rotation is read by the Magnus lift and the torque only, grad p by the pressure
  // force only: without them no vorticity or gradient field is made.
  CouplingConfig c;
  c.magnus = false;
  c.rotation_torque = false;
  c.pressure_force = false;
  const CouplingModels some(c);
  EXPECT_FALSE(some.reads().rotation);
  EXPECT_FALSE(some.reads().pressure_gradient);
  EXPECT_TRUE(some.writes().drag);
  EXPECT_FALSE(some.writes().magnus || some.writes().pressure || some.writes().torque);
  EXPECT_EQ(some.descriptions().size(), 2u);
  c.rotation_torque = true;
  EXPECT_TRUE(CouplingModels(c).reads().rotation);

  CouplingConfig none;
  none.drag = none.magnus = none.pressure_force = none.rotation_torque = none.heat_transfer = false;
  const CouplingModels empty(none);
  const ForceParts nothing = empty.writes();
  EXPECT_FALSE(nothing.drag || nothing.magnus || nothing.pressure || nothing.torque ||
               nothing.heat);
  EXPECT_TRUE(empty.descriptions().empty());
}

TEST(CouplingModels, TheDemSubstepAppliesTheModelsSubstepLaws) {
  // One forced sub-step of a single parcel: the force parts it stores are the models'
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
  GasForcing f;
  int k = 0;
  for (ParcelColumn* c :
       {&f.gas_u, &f.gas_v, &f.gas_rotation, &f.gas_temperature, &f.drag_coefficient,
        &f.magnus_coefficient, &f.torque_coefficient, &f.heat_coefficient, &f.impulse_x,
        &f.impulse_y, &f.work, &f.heat_in, &f.relative_rotation}) {
    *c = s.attach_column({"forcing_" + std::to_string(k++), "", false, false});
  }
  f.drag = f.magnus = f.torque = f.heat = true;
  s.set_gas_forcing(f);
  const double ug = 150.0, vg = 20.0, rot = -4000.0, Tg = 900.0;
  const double K = 3.1e-7, M = -2.4e-13, kappa = 4.0e-17, H = 2.0e-6;
  s.column(f.gas_u)[0] = ug;
  s.column(f.gas_v)[0] = vg;
  s.column(f.gas_rotation)[0] = rot;
  s.column(f.gas_temperature)[0] = Tg;
  s.column(f.drag_coefficient)[0] = K;
  s.column(f.magnus_coefficient)[0] = M;
  s.column(f.torque_coefficient)[0] = kappa;
  s.column(f.heat_coefficient)[0] = H;
  s.step(s.stable_time_step());
  const Vec2 u_r{ug - p.vx, vg - p.vy};
  const double w_r = rot - p.omega;
  const Vec2 drag = DragModel::force(K, u_r), lift = MagnusModel::force(M, w_r, u_r);
  EXPECT_EQ(s.drag_fx[0], drag.x);
  EXPECT_EQ(s.drag_fy[0], drag.y);
  EXPECT_EQ(s.magnus_fx[0], lift.x);
  EXPECT_EQ(s.magnus_fy[0], lift.y);
  EXPECT_EQ(s.fluid_torque[0], RotationTorqueModel::torque(kappa, w_r));
  EXPECT_EQ(s.heat_rate[0], HeatTransferModel::heat_flow(H, Tg, p.temperature));
  EXPECT_EQ(s.column(f.relative_rotation)[0], w_r);
}
