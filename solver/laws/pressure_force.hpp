#pragma once
// Pressure-gradient force (Table 1, docs/coupling.md): F = -V_p grad p per real particle (the
// paper prints +). The gas feels it through alpha_g grad p, so it is not exchanged.
#include "solver/core/vec2.hpp"

namespace dustlift::aero {

/// Pressure-gradient force -V_p grad p on one real particle of diameter d.
inline Vec2 pressure_force(double d, Vec2 grad_p) {
  const double vp = 3.14159265358979323846 / 6.0 * d * d * d;
  return grad_p * (-vp);
}

}  // namespace dustlift::aero
