#pragma once
// The pressure-gradient force (Table 1) as an effect: F = -V_p grad p per real particle
// (laws/pressure_force.hpp), frozen over the CFD step, so the sampled force is the sub-step's as
// it is. Not exchanged: the gas feels it through alpha_g grad p.
#include <string>

#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/laws/pressure_force.hpp"

namespace dustlift {

class PressureForceEffect final : public BatchedEffect<PressureForceEffect> {
 public:
  /// Where its functor runs in the DEM's forced sub-step (Table 1's order; effect_list.cpp).
  static constexpr int kPosition = 3;
  static bool active(const CouplingConfig& c) { return c.pressure_force; }
  PressureForceEffect() = default;
  explicit PressureForceEffect(const CouplingConfig&) {}
  std::string description() const override { return "pressure-gradient force -V_p grad p"; }
  GasReads reads() const override { return {.pressure_gradient = true}; }
  void attach(ParcelTable& t) override {
    namespace c = effect_columns;
    fx_ = c::part(t, "pressure_fx", "N", ForcePart::Pressure, "force_pressure", 0,
                  "parcels/pressure_fx");
    fy_ = c::part(t, "pressure_fy", "N", ForcePart::Pressure, "force_pressure", 1,
                  "parcels/pressure_fy");
  }

  struct Columns {
    double *fx, *fy;
  };
  Columns columns(ParcelTable& t) const { return {t.column(fx_).data(), t.column(fy_).data()}; }
  void coefficient(const ModelInput& in, std::size_t k, Columns& out) const {
    const Vec2 f = aero::pressure_force(in.parcel.diameter, {in.gas.dpdx, in.gas.dpdy});
    out.fx[k] = f.x;
    out.fy[k] = f.y;
  }

  /// The sub-step: the sampled force, not exchanged.
  struct Substep : SubstepRoles {
    static constexpr bool kLocal = true;
    struct Part {};  // the sampled force is its part already
    const double *fx, *fy;
    Part force(std::size_t i, SubstepParcel& p) const {
      p.local_x += fx[i];
      p.local_y += fy[i];
      return {};
    }
  };
  Substep substep(ParcelTable& t, const FrozenGas&) const {
    return {{}, t.column(fx_).data(), t.column(fy_).data()};
  }

 private:
  ParcelColumn fx_, fy_;
};

}  // namespace dustlift
