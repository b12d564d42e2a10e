#include "solver/coupling/coupling_models.hpp"

#include <numbers>
#include <sstream>

#include "solver/coupling/aerodynamics.hpp"

namespace dustlift {
namespace {

class DragModel final : public BatchedCouplingModel<DragModel> {
 public:
  explicit DragModel(const CouplingConfig& c) : compressible_(c.compressibility_correction), xi2_(c.volume_fraction) {}
  std::string description() const override {
    std::string s = "drag: Clift-Gauvin";
    if (compressible_) s += " x Parmar xi_1(M, Re)";
    if (xi2_.kind == aero::VolumeFractionCorrection::Kind::Sangani) s += " x Sangani xi_2(alpha_g)";
    if (xi2_.kind == aero::VolumeFractionCorrection::Kind::Linear) s += " x (1 + 5.94 alpha_p)";
    if (xi2_.kind != aero::VolumeFractionCorrection::Kind::None && xi2_.phi_cap < 1.0) {
      std::ostringstream cap;
      cap << " (alpha_p capped at " << xi2_.phi_cap << ")";
      s += cap.str();
    }
    return s;
  }
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    const ParcelAtSample& p = in.parcel;
    const double slip = in.slip;
    const aero::GasAtParcel at{g.rho, {g.u, g.v}, g.mu, g.c, g.alpha_g};
    out.drag = aero::drag_coefficient(at, slip, p.diameter, compressible_, xi2_);
  }

 private:
  bool compressible_;
  aero::VolumeFractionCorrection xi2_;
};

class MagnusModel final : public BatchedCouplingModel<MagnusModel> {
 public:
  explicit MagnusModel(const CouplingConfig& c)
      : c_lm_(c.magnus_coefficient), lun_liu_(c.lun_liu), paper_(c.magnus_convention == aero::MagnusConvention::Paper) {}
  std::string description() const override {
    std::ostringstream s;
    s << "Magnus lift: C_LM = " << c_lm_ << (lun_liu_ ? " x Lun-Liu f(Re)" : "")
      << (paper_ ? " (paper convention)" : " (standard convention)");
    return s.str();
  }
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    const ParcelAtSample& p = in.parcel;
    const double re = in.re;
    const double c_lm = c_lm_ * (lun_liu_ ? aero::lun_liu_factor(re) : 1.0);
    const double d = p.diameter;
    out.magnus = c_lm * std::numbers::pi / 8.0 * g.rho * d * d * d;  // aero::magnus_force / (w_r z x u_r)
  }

 private:
  double c_lm_;
  bool lun_liu_, paper_;
};

class PressureForceModel final : public BatchedCouplingModel<PressureForceModel> {
 public:
  std::string description() const override { return "pressure-gradient force -V_p grad p"; }
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    const ParcelAtSample& p = in.parcel;
    const Vec2 f = aero::pressure_force(p.diameter, {g.dpdx, g.dpdy});
    out.pressure_fx = f.x;
    out.pressure_fy = f.y;
  }
};

class RotationTorqueModel final : public BatchedCouplingModel<RotationTorqueModel> {
 public:
  explicit RotationTorqueModel(const CouplingConfig& c) : stokes_below_(c.torque_stokes_below) {}
  std::string description() const override { return "rotational friction torque (Dennis, Singh & Ingham 1980)"; }
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    const ParcelAtSample& p = in.parcel;
    // M = kappa w_r with kappa = M(w_r0) / w_r0 at the step's relative rotation (the torque is
    // odd in w_r); at w_r0 = 0 the Stokes slope pi mu d^3.
    const double d = p.diameter;
    const double w0 = aero::relative_rotation(g.vorticity, p.omega);
    out.torque = w0 != 0.0 ? aero::rotation_torque(g.rho, g.mu, d, w0, stokes_below_) / w0
                           : std::numbers::pi * g.mu * d * d * d;
  }

 private:
  double stokes_below_;
};

class HeatTransferModel final : public BatchedCouplingModel<HeatTransferModel> {
 public:
  std::string description() const override { return "heat transfer (Ranz-Marshall) and particle temperature"; }
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    const ParcelAtSample& p = in.parcel;
    const double re = in.re;
    // Q = pi d^2 (Nu lambda / d) (T_g - T_p) = H (T_g - T_p) (aero::heat_flow).
    out.heat = std::numbers::pi * p.diameter * g.lambda * aero::nusselt_ranz_marshall(re, g.mu * g.cp / g.lambda);
  }
};

}  // namespace

std::vector<std::unique_ptr<CouplingModel>> build_coupling_models(const CouplingConfig& c) {
  std::vector<std::unique_ptr<CouplingModel>> m;
  if (c.drag) m.push_back(std::make_unique<DragModel>(c));
  if (c.magnus) m.push_back(std::make_unique<MagnusModel>(c));
  if (c.pressure_force) m.push_back(std::make_unique<PressureForceModel>());
  if (c.rotation_torque) m.push_back(std::make_unique<RotationTorqueModel>(c));
  if (c.heat_transfer) m.push_back(std::make_unique<HeatTransferModel>());
  return m;
}

}  // namespace dustlift
