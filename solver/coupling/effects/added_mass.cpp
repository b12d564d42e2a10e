#include "solver/coupling/effects/added_mass.hpp"

#include <numbers>

#include "solver/coupling/coupling_config.hpp"

namespace dustlift {

AddedMassEffect::AddedMassEffect(const CouplingConfig& c)
    : correction_(c.added_mass_volume_fraction),
      acceleration_(c.added_mass_fluid_acceleration),
      two_way_(c.two_way) {}

std::string AddedMassEffect::description() const {
  using V = aero::AddedMassVolumeFraction;
  return std::string(
             "added mass (inviscid unsteady): C_M = 1/2 (1 + 1.8 Ma^2 + 7.6 Ma^4) "
             "(Parmar et al. 2008)") +
         (correction_ == V::Beguin  ? " x (1 + 0.68 alpha_p^2) (Beguin et al. 2016)"
          : correction_ == V::Zuber ? " x (1 + 2 alpha_p)/(1 - alpha_p) (Zuber 1964)"
                                    : "") +
         (acceleration_ == aero::FluidAcceleration::Resolved
              ? "; D(rho u)/Dt of the resolved gas, implicit where the gas feels the cloud"
              : "; D(rho u)/Dt taken as -grad p (Ling et al. 2012)") +
         "; added to the parcel's inertia";
}

GasReads AddedMassEffect::reads() const {
  if (acceleration_ == aero::FluidAcceleration::Resolved) return {.momentum_gradient = true};
  return {.pressure_gradient = true};
}

void AddedMassEffect::attach(ParcelTable& t) {
  namespace c = effect_columns;
  added_mass_ = c::coefficient(t, "added_mass", "kg");
  fluid_x_ = c::coefficient(t, "added_mass_gas_x", "N");
  fluid_y_ = c::coefficient(t, "added_mass_gas_y", "N");
  inv_total_mass_ = c::coefficient(t, "inv_total_mass", "1/kg");
  fx_ = c::part(t, "added_mass_fx", "N", ForcePart::AddedMass, "force_added_mass", 0, "");
  fy_ = c::part(t, "added_mass_fy", "N", ForcePart::AddedMass, "force_added_mass", 1, "");
  if (acceleration_ == aero::FluidAcceleration::Resolved) {
    rho_u_ = c::carried(t, "added_mass_rho_u", "kg/(m^2 s)");
    rho_v_ = c::carried(t, "added_mass_rho_v", "kg/(m^2 s)");
    rho_ = c::carried(t, "added_mass_rho", "kg/m^3");
    sampled_at_ = c::carried(t, "added_mass_sampled_at", "s");
    sampled_ = c::carried(t, "added_mass_sampled", "1");
    rate_x_ = c::carried(t, "added_mass_rate_x", "kg/(m^2 s^2)");
    rate_y_ = c::carried(t, "added_mass_rate_y", "kg/(m^2 s^2)");
  }
}

void AddedMassEffect::coefficients(const ModelInput* in, std::size_t k0, std::size_t n,
                                   ParcelTable& t, const StepContext& step) const {
  double* m_a = t.column(added_mass_).data();
  double* fluid_x = t.column(fluid_x_).data();
  double* fluid_y = t.column(fluid_y_).data();
  double* inv_total = t.column(inv_total_mass_).data();
  const bool resolved = acceleration_ == aero::FluidAcceleration::Resolved;
  double* rho_u = resolved ? t.column(rho_u_).data() : nullptr;
  double* rho_v = resolved ? t.column(rho_v_).data() : nullptr;
  double* rho = resolved ? t.column(rho_).data() : nullptr;
  double* sampled_at = resolved ? t.column(sampled_at_).data() : nullptr;
  double* sampled = resolved ? t.column(sampled_).data() : nullptr;
  double* rate_x = resolved ? t.column(rate_x_).data() : nullptr;
  double* rate_y = resolved ? t.column(rate_y_).data() : nullptr;
  for (std::size_t q = 0; q < n; ++q) {
    const std::size_t k = k0 + q;
    const GasSample& g = in[q].gas;
    const ParcelAtSample& p = in[q].parcel;
    const double d = p.diameter;
    const double c_m = aero::added_mass_coefficient(in[q].slip / g.c, 1.0 - g.alpha_g, correction_);
    const double cv = c_m * (std::numbers::pi / 6.0 * d * d * d);  // C_M V_p
    Vec2 fluid;
    if (resolved) {
      // The rates along the parcel's path since its last sample (none at the first).
      const double mx = g.rho_u, my = g.rho_v;
      const double elapsed = step.time - sampled_at[k];
      const bool known = sampled[k] != 0.0 && elapsed > 0.0;
      const Vec2 along =
          known ? Vec2{(mx - rho_u[k]) / elapsed, (my - rho_v[k]) / elapsed} : Vec2{};
      const double drho = known ? (g.rho - rho[k]) / elapsed : 0.0;
      const Vec2 measured = aero::momentum_rate_following_gas(
          along, {g.u - p.vx, g.v - p.vy}, {g.dx_rho_u, g.dy_rho_u, g.dx_rho_v, g.dy_rho_v});
      // Implicit where the gas feels the cloud: the reaction of these forces is in what the gas
      // showed over the last step.
      const double w = two_way_ ? aero::virtual_mass_weight(g.alpha_g, c_m) : 0.0;
      const Vec2 rate{(1.0 - w) * measured.x + w * rate_x[k],
                      (1.0 - w) * measured.y + w * rate_y[k]};
      rho_u[k] = mx;
      rho_v[k] = my;
      rho[k] = g.rho;
      sampled_at[k] = step.time;
      sampled[k] = 1.0;
      rate_x[k] = rate.x;
      rate_y[k] = rate.y;
      // F_g = C_M V_p [D(rho u)/Dt - v d(rho)/dt|_p] (Parmar et al. 2008).
      fluid = {cv * (rate.x - p.vx * drho), cv * (rate.y - p.vy * drho)};
    } else {
      fluid = {-cv * g.dpdx, -cv * g.dpdy};
    }
    m_a[k] = cv * g.rho;
    fluid_x[k] = fluid.x;
    fluid_y[k] = fluid.y;
    inv_total[k] = 1.0 / (p.mass + m_a[k]);
  }
}

}  // namespace dustlift
