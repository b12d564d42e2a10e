#pragma once
// The inviscid-unsteady (added-mass) force (laws/added_mass.hpp) as an effect: each sub-step
// solves (m + m_a) dv/dt = F + F_g with the added mass m_a = C_M rho_g V_p and the fluid part
// F_g = C_M V_p D(rho_g u)/Dt, and the force F_g - m_a dv/dt is exchanged with the gas like drag.
#include <string>

#include "solver/core/vec2.hpp"
#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/laws/added_mass.hpp"

namespace dustlift {

struct CouplingConfig;

class AddedMassEffect final : public BatchedEffect<AddedMassEffect> {
 public:
  explicit AddedMassEffect(const CouplingConfig& c);
  std::string description() const override;
  GasReads reads() const override { return {.pressure_gradient = true}; }
  void attach(ParcelTable& t) override;

  struct Columns {
    double *added_mass, *fluid_x, *fluid_y, *inv_total_mass;
  };
  Columns columns(ParcelTable& t) const {
    return {t.column(added_mass_).data(), t.column(fluid_x_).data(), t.column(fluid_y_).data(),
            t.column(inv_total_mass_).data()};
  }
  /// m_a = C_M rho_g V_p, F_g = C_M V_p D(rho u)/Dt and 1 / (m + m_a) at the step's gas and
  /// slip (Ma = slip / c, phi = 1 - alpha_g).
  void coefficient(const ModelInput& in, std::size_t k, Columns& out) const;

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
    const Columns c = columns(t);
    return {{},           {t.column(fx_).data(), t.column(fy_).data()},
            c.added_mass, c.fluid_x,
            c.fluid_y,    c.inv_total_mass};
  }

 private:
  aero::AddedMassVolumeFraction correction_;
  ParcelColumn added_mass_, fluid_x_, fluid_y_, inv_total_mass_, fx_, fy_;
};

}  // namespace dustlift
