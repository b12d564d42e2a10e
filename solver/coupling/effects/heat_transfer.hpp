#pragma once
// Heat transfer (eqs. 7-10, Ranz & Marshall 1952) as an effect: Q = H (T_g - T_p) per real
// particle with the conductance H at the CFD step's Re (laws/heat_transfer.hpp); exchanged with
// the gas (eq. 15) and made implicit where it is stiff.
#include <string>

#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/laws/heat_transfer.hpp"

namespace dustlift {

class HeatTransferEffect final : public BatchedEffect<HeatTransferEffect>, public StiffColumns {
 public:
  /// Where its functor runs in the DEM's forced sub-step (Table 1's order; effect_list.cpp).
  static constexpr int kPosition = 6;
  static bool active(const CouplingConfig& c) { return c.heat_transfer; }
  HeatTransferEffect() = default;
  explicit HeatTransferEffect(const CouplingConfig&) {}
  std::string description() const override {
    return "heat transfer (Ranz-Marshall) and particle temperature";
  }
  void attach(ParcelTable& t) override {
    namespace c = effect_columns;
    attach_stiff(t, "heat_coefficient", "W/K");
    rate_ = c::part(t, "heat_rate", "W", ForcePart::Heat, "", 0, "parcels/heat_rate");
  }
  std::optional<StiffCoefficient> stiff_heat() const override { return stiff(); }
  /// H = pi d lambda Nu, Nu = Ranz-Marshall at the step's Re and the gas's Prandtl number.
  void coefficient(const ModelInput& in, std::size_t k, Columns& out) const {
    const GasSample& g = in.gas;
    out.sampled[k] = out.applied[k] = aero::heat_conductance(
        in.parcel.diameter, g.lambda, aero::nusselt_ranz_marshall(in.re, g.mu * g.cp / g.lambda));
  }

  /// The sub-step: Q = H (T_g - T).
  struct Substep : SubstepRoles, StoresValue {
    static constexpr bool kHeat = true;
    const double *temperature, *H;
    double force(std::size_t i, SubstepParcel& p) const {
      const double q = aero::linear_heat_flow(H[i], temperature[i], p.temperature);
      p.heat += q;
      return q;
    }
  };
  Substep substep(ParcelTable& t, const FrozenGas& g) const {
    return {{}, {t.column(rate_).data()}, g.temperature, t.column(applied_).data()};
  }

 private:
  ParcelColumn rate_;
};

}  // namespace dustlift
