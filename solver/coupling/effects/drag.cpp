#include "solver/coupling/effects/drag.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "solver/coupling/coupling_config.hpp"
#include "solver/laws/dense_drag.hpp"

namespace dustlift {

DragEffect::DragEffect(const CouplingConfig& c)
    : compressible_(c.compressibility_correction), xi2_(c.volume_fraction) {}

std::string DragEffect::description() const {
  using Kind = aero::VolumeFractionCorrection::Kind;
  if (xi2_.kind == Kind::Tenneti)
    return "drag: Tenneti et al. 2011 (dense random arrays, Schiller-Naumann at Re_m; mean "
           "pressure drag taken out)";
  if (xi2_.kind == Kind::Osnes)
    return "drag: Osnes et al. 2023 (Loth et al. 2021 isolated sphere, volume-fraction and Mach "
           "terms of random suspensions; mean pressure drag taken out)";
  std::string s = "drag: Clift-Gauvin";
  if (compressible_) s += " x Parmar xi_1(M, Re)";
  if (xi2_.kind == Kind::Sangani) s += " x Sangani xi_2(alpha_g)";
  if (xi2_.kind == Kind::Linear) s += " x (1 + 5.94 alpha_p)";
  if (xi2_.kind != Kind::None && xi2_.phi_cap < 1.0)
    s += fmt::format(" (alpha_p capped at {:g})", xi2_.phi_cap);
  return s;
}

std::vector<std::string> DragEffect::validity(const FlowEnvelope& e) const {
  using Kind = aero::VolumeFractionCorrection::Kind;
  std::vector<std::string> out;
  const double phi = std::min(e.max_volume_fraction, xi2_.phi_cap);
  // The packed bed's reference: Ergun's law in the Stokes limit, per 3 pi mu d.
  const double ergun = aero::ergun_drag_factor(0.0, phi);
  const auto beyond = [&](const char* law, double limit, double factor) {
    out.push_back(fmt::format(
        "drag: {} holds to alpha_p = {:g}; the particles pack to {:.2f}, where it gives "
        "{:.3g} x 3 pi mu d u_r in the Stokes limit against {:.3g} from Ergun's packed-bed law "
        "(mean pressure drag taken out)",
        law, limit, phi, factor, ergun));
  };
  if (xi2_.kind == Kind::Sangani && phi > 0.3)
    beyond("Sangani's (1 + 2 phi)/(1 - phi)^3 (for dilute arrays; ppiclF caps it there)", 0.3,
           aero::xi2(1.0 - phi, xi2_));
  if (xi2_.kind == Kind::Linear && phi > 0.5)
    beyond("the linear 1 + 5.94 phi (MFC caps it there)", 0.5, aero::xi2(1.0 - phi, xi2_));
  if (xi2_.kind == Kind::Tenneti) {
    if (phi > 0.5) beyond("Tenneti et al.'s fit", 0.5, aero::tenneti_drag_factor(0.0, phi));
    const double re_m = (1.0 - phi) * e.max_reynolds;
    if (re_m > 300.0)
      out.push_back(fmt::format(
          "drag: Tenneti et al. fitted Re_m <= 300; a particle at rest in the fastest gas has "
          "Re_m = {:.0f}",
          re_m));
    if (e.max_mach > 0.3)
      out.push_back(fmt::format(
          "drag: Tenneti et al.'s fit is incompressible; the slip Mach number reaches {:.2f}",
          e.max_mach));
  }
  if (xi2_.kind == Kind::Osnes && phi > 0.4)
    beyond("Osnes et al.'s fit (particle-resolved data up to phi = 0.4)", 0.4,
           aero::osnes_drag_factor(0.0, 0.0, 0.0, 1.4, phi));
  if (xi2_.kind == Kind::Osnes && e.max_mach > 1.2)
    out.push_back(fmt::format(
        "drag: Osnes et al. fitted subsonic to weakly supersonic slip; the slip Mach number "
        "reaches {:.2f}",
        e.max_mach));
  if (compressible_ && xi2_.kind != Kind::Tenneti && xi2_.kind != Kind::Osnes && e.max_mach > 1.75)
    out.push_back(fmt::format(
        "drag: Parmar et al.'s compressible fits end at M = 1.75 (held beyond); the slip Mach "
        "number reaches {:.2f}",
        e.max_mach));
  return out;
}

void DragEffect::attach(ParcelTable& t) {
  namespace c = effect_columns;
  attach_stiff(t, "drag_coefficient", "N s/m");
  fx_ = c::part(t, "drag_fx", "N", ForcePart::Drag, "force_drag", 0, "parcels/drag_fx");
  fy_ = c::part(t, "drag_fy", "N", ForcePart::Drag, "force_drag", 1, "parcels/drag_fy");
}

}  // namespace dustlift
