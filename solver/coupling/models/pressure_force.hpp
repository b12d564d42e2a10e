#pragma once
// Pressure-gradient force (Table 1, docs/coupling.md): F = -V_p grad p per real particle
// (the paper prints +). The gradient is frozen over the CFD step, so the sampled force is the
// sub-step's as it is (ParcelSystem's pressure_fx/fy columns, added to the parcel's force and
// not exchanged: the gas feels it through alpha_g grad p).
#include <string>

#include "solver/core/vec2.hpp"
#include "solver/coupling/models/coupling_model.hpp"

namespace dustlift {

namespace aero {

/// Pressure-gradient force -V_p grad p on one real particle of diameter d.
inline Vec2 pressure_force(double d, Vec2 grad_p) {
  const double vp = 3.14159265358979323846 / 6.0 * d * d * d;
  return grad_p * (-vp);
}

}  // namespace aero

class PressureForceModel final : public BatchedCouplingModel<PressureForceModel> {
 public:
  static constexpr ModelTraits kTraits{.reads = {.pressure_gradient = true},
                                       .writes = {.pressure = true}};

  std::string description() const override { return "pressure-gradient force -V_p grad p"; }
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    const Vec2 f = aero::pressure_force(in.parcel.diameter, {g.dpdx, g.dpdy});
    out.pressure_fx = f.x;
    out.pressure_fy = f.y;
  }
};

}  // namespace dustlift
