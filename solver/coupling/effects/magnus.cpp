#include "solver/coupling/effects/magnus.hpp"

#include <sstream>

#include "solver/coupling/coupling_config.hpp"

namespace dustlift {

MagnusEffect::MagnusEffect(const CouplingConfig& c)
    : c_lm_(c.magnus_coefficient), lun_liu_(c.lun_liu), convention_(c.magnus_convention) {}

std::string MagnusEffect::description() const {
  std::ostringstream s;
  s << "Magnus lift: C_LM = " << c_lm_ << (lun_liu_ ? " x Lun-Liu f(Re)" : "")
    << (convention_ == aero::MagnusConvention::Paper ? " (paper convention)"
                                                     : " (standard convention)");
  return s.str();
}

void MagnusEffect::attach(ParcelTable& t) {
  namespace c = effect_columns;
  coefficient_ = c::coefficient(t, "magnus_coefficient", "N s^2/m^2");
  fx_ = c::part(t, "magnus_fx", "N", ForcePart::Magnus, "force_magnus", 0, "parcels/magnus_fx");
  fy_ = c::part(t, "magnus_fy", "N", ForcePart::Magnus, "force_magnus", 1, "parcels/magnus_fy");
}

}  // namespace dustlift
