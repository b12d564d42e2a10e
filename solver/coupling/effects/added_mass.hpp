#pragma once
// The inviscid-unsteady (added-mass) force (laws/added_mass.hpp) as an effect: each sub-step
// solves (m + m_a) dv/dt = F + F_g with the added mass m_a = C_M rho_g V_p and the fluid part
// F_g = C_M V_p [D(rho_g u)/Dt - v d(rho_g)/dt|_p], and the force F_g - m_a dv/dt is exchanged
// with the gas like drag. The gas's momentum rate D(rho u)/Dt is the resolved flow's: the
// sampled rho u's rate along the parcel's path since its last sample, plus (u - v) . grad(rho u)
// (`resolved`), made implicit in a cloud the gas feels; or Ling et al. (2012)'s -grad p
// (`pressure_gradient`, a dilute cloud's approximation). docs/coupling.md gives every choice.
#include <string>

#include "solver/core/vec2.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/laws/added_mass.hpp"

namespace dustlift {

class AddedMassEffect final : public CouplingEffect {
 public:
  /// Where its functor runs in the DEM's forced sub-step (Table 1's order; effect_list.cpp).
  static constexpr int kPosition = 4;
  static bool active(const CouplingConfig& c) { return c.added_mass; }
  explicit AddedMassEffect(const CouplingConfig& c);
  std::string description() const override;
  GasReads reads() const override;
  void attach(ParcelTable& t) override;
  void coefficients(const ModelInput* in, std::size_t k0, std::size_t n, ParcelTable& t,
                    const StepContext& step) const override;

  /// The sub-step: the acceleration with the added mass, then the force at it.
  struct Substep : SubstepRoles, StoresForce {
    static constexpr bool kExchanges = true, kInertia = true;
    const double *added_mass, *fluid_x, *fluid_y, *inv_total_mass;
    /// (m + m_a) dv/dt = F + F_g + m g.
    Vec2 acceleration(std::size_t i, const SubstepParcel& p, Vec2 force, Vec2 gravity) const {
      const Vec2 a =
          aero::added_mass_acceleration(force, {fluid_x[i], fluid_y[i]}, inv_total_mass[i]);
      const double weight_share = inv_total_mass[i] / p.inv_mass;  // m / (m + m_a)
      return {a.x + gravity.x * weight_share, a.y + gravity.y * weight_share};
    }
    Vec2 after(std::size_t i, SubstepParcel& p) const {
      const Vec2 f =
          aero::added_mass_force_at({fluid_x[i], fluid_y[i]}, added_mass[i], {p.ax, p.ay});
      p.exchanged_x += f.x;
      p.exchanged_y += f.y;
      return f;
    }
  };
  Substep substep(ParcelTable& t, const FrozenGas&) const {
    return {{},
            {t.column(fx_).data(), t.column(fy_).data()},
            t.column(added_mass_).data(),
            t.column(fluid_x_).data(),
            t.column(fluid_y_).data(),
            t.column(inv_total_mass_).data()};
  }

 private:
  aero::AddedMassVolumeFraction correction_;
  aero::FluidAcceleration acceleration_;
  bool two_way_;
  ParcelColumn added_mass_, fluid_x_, fluid_y_, inv_total_mass_, fx_, fy_;
  /// The resolved rate's memory (kept in checkpoints): rho u, rho v and rho at the parcel's
  /// last sample and its time (0 before the first), and the rate used then.
  ParcelColumn rho_u_, rho_v_, rho_, sampled_at_, sampled_, rate_x_, rate_y_;
};

}  // namespace dustlift
