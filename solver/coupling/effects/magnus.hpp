#pragma once
// Magnus lift (Table 1) as an effect: F = M w_r z x u_r per real particle with
// M = s C_LM (pi/8) rho d^3 (laws/magnus.hpp; the optional Lun-Liu factor at the step's Re);
// exchanged with the gas like drag (eq. 13).
#include <string>

#include "solver/core/vec2.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/laws/magnus.hpp"

namespace dustlift {

class MagnusEffect final : public BatchedEffect<MagnusEffect> {
 public:
  /// Where its functor runs in the DEM's forced sub-step (Table 1's order; effect_list.cpp).
  static constexpr int kPosition = 2;
  static bool active(const CouplingConfig& c) { return c.magnus; }
  explicit MagnusEffect(const CouplingConfig& c);
  std::string description() const override;
  GasReads reads() const override { return {.rotation = true}; }
  void attach(ParcelTable& t) override;

  struct Columns {
    double* M;
  };
  Columns columns(ParcelTable& t) const { return {t.column(coefficient_).data()}; }
  void coefficient(const ModelInput& in, std::size_t k, Columns& out) const {
    const double c_lm = c_lm_ * (lun_liu_ ? aero::lun_liu_factor(in.re) : 1.0);
    out.M[k] = aero::magnus_coefficient(c_lm, convention_, in.gas.rho, in.parcel.diameter);
  }

  /// The sub-step: F = M (Omega_g - w) z x (u_g - v), exchanged with the gas.
  struct Substep : SubstepRoles, StoresForce {
    static constexpr bool kExchanges = true;
    const double *u, *v, *rotation, *M;
    Vec2 force(std::size_t i, SubstepParcel& p) const {
      const Vec2 f = aero::magnus_lift(M[i], rotation[i] - p.omega, {u[i] - p.vx, v[i] - p.vy});
      p.exchanged_x += f.x;
      p.exchanged_y += f.y;
      return f;
    }
  };
  Substep substep(ParcelTable& t, const FrozenGas& g) const {
    return {{},         {t.column(fx_).data(), t.column(fy_).data()},
            g.u,        g.v,
            g.rotation, t.column(coefficient_).data()};
  }

 private:
  double c_lm_;
  bool lun_liu_;
  aero::MagnusConvention convention_;
  ParcelColumn coefficient_, fx_, fy_;
};

}  // namespace dustlift
