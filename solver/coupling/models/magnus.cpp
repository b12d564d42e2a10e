#include "solver/coupling/models/magnus.hpp"

#include <cmath>
#include <sstream>

#include "solver/coupling/coupling_config.hpp"

namespace dustlift::aero {

double lun_liu_factor(double re) {
  return re <= 1.0 ? 1.0 : 0.178 + 0.822 * std::pow(re, -0.522);
}

Vec2 magnus_force(double rho, double d, Vec2 u_r, double omega_rel, double c_lm,
                  MagnusConvention conv) {
  return MagnusModel::force(MagnusModel::coefficient(c_lm, conv, rho, d), omega_rel, u_r);
}

}  // namespace dustlift::aero

namespace dustlift {

MagnusModel::MagnusModel(const CouplingConfig& c)
    : c_lm_(c.magnus_coefficient), lun_liu_(c.lun_liu), convention_(c.magnus_convention) {}

std::string MagnusModel::description() const {
  std::ostringstream s;
  s << "Magnus lift: C_LM = " << c_lm_ << (lun_liu_ ? " x Lun-Liu f(Re)" : "")
    << (convention_ == aero::MagnusConvention::Paper ? " (paper convention)"
                                                     : " (standard convention)");
  return s.str();
}

}  // namespace dustlift
