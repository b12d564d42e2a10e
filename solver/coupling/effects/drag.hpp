#pragma once
// Drag (Table 1) as an effect: F = K u_r per real particle with K = beta (laws/drag.hpp) at the
// CFD step's slip; exchanged with the gas (eq. 13) and made implicit where it is stiff.
#include <string>
#include <vector>

#include "solver/core/vec2.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/laws/drag.hpp"

namespace dustlift {

class DragEffect final : public BatchedEffect<DragEffect>, public StiffColumns {
 public:
  /// Where its functor runs in the DEM's forced sub-step (Table 1's order; effect_list.cpp).
  static constexpr int kPosition = 1;
  static bool active(const CouplingConfig& c) { return c.drag; }
  explicit DragEffect(const CouplingConfig& c);
  std::string description() const override;
  std::vector<std::string> validity(const FlowEnvelope& e) const override;
  void attach(ParcelTable& t) override;
  std::optional<StiffCoefficient> stiff_momentum() const override { return stiff(); }
  /// K = beta (aero::drag_coefficient) at the step's slip.
  void coefficient(const ModelInput& in, std::size_t k, Columns& out) const {
    const GasSample& g = in.gas;
    const aero::GasAtParcel at{g.rho, {g.u, g.v}, g.mu, g.c, g.alpha_g, g.gamma};
    out.sampled[k] = out.applied[k] =
        aero::drag_coefficient(at, in.slip, in.parcel.diameter, compressible_, xi2_);
  }

  /// The sub-step: F = K (u_g - v), exchanged with the gas.
  struct Substep : SubstepRoles, StoresForce {
    static constexpr bool kExchanges = true;
    const double *u, *v, *K;
    Vec2 force(std::size_t i, SubstepParcel& p) const {
      const Vec2 f = aero::linear_drag(K[i], {u[i] - p.vx, v[i] - p.vy});
      p.exchanged_x += f.x;
      p.exchanged_y += f.y;
      return f;
    }
  };
  Substep substep(ParcelTable& t, const FrozenGas& g) const {
    return {{}, {t.column(fx_).data(), t.column(fy_).data()}, g.u, g.v, t.column(applied_).data()};
  }

 private:
  bool compressible_;
  aero::VolumeFractionCorrection xi2_;
  ParcelColumn fx_, fy_;
};

}  // namespace dustlift
