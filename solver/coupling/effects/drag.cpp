#include "solver/coupling/effects/drag.hpp"

#include <sstream>

#include "solver/coupling/coupling_config.hpp"

namespace dustlift {

DragEffect::DragEffect(const CouplingConfig& c)
    : compressible_(c.compressibility_correction), xi2_(c.volume_fraction) {}

std::string DragEffect::description() const {
  using Kind = aero::VolumeFractionCorrection::Kind;
  std::string s = "drag: Clift-Gauvin";
  if (compressible_) s += " x Parmar xi_1(M, Re)";
  if (xi2_.kind == Kind::Sangani) s += " x Sangani xi_2(alpha_g)";
  if (xi2_.kind == Kind::Linear) s += " x (1 + 5.94 alpha_p)";
  if (xi2_.kind == Kind::Tenneti)
    s += " at Re_m, dense arrays by Tenneti et al. 2011 (mean pressure drag taken out)";
  if (xi2_.kind != Kind::None && xi2_.phi_cap < 1.0) {
    std::ostringstream cap;
    cap << " (alpha_p capped at " << xi2_.phi_cap << ")";
    s += cap.str();
  }
  return s;
}

std::vector<std::string> DragEffect::validity(const FlowEnvelope&) const {
  return {};
}

void DragEffect::attach(ParcelTable& t) {
  namespace c = effect_columns;
  // The sampled coefficient is read for resting parcels in later steps (the implicit exchange
  // sums every parcel of a cell): kept in checkpoints.
  sampled_ = c::carried(t, "drag_coefficient_sampled", "N s/m");
  applied_ = c::coefficient(t, "drag_coefficient", "N s/m");
  fx_ = c::part(t, "drag_fx", "N", ForcePart::Drag, "force_drag", 0, "parcels/drag_fx");
  fy_ = c::part(t, "drag_fy", "N", ForcePart::Drag, "force_drag", 1, "parcels/drag_fy");
}

}  // namespace dustlift
