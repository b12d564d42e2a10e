#pragma once
// Names of the gas state's components, so that an array indexed by component says which one
// it reads (the arrays stay plain arrays: these convert to their index).

namespace dustlift {

/// The conserved state with a = alpha_g: a rho (mass), a rho u and a rho v (momentum), a E
/// (total energy), per m^3. Indexes GasSolver::conserved() and source() and every
/// per-component array of the solver (face fluxes, stage rows).
struct Conserved {
  enum Component : int { kMass = 0, kMomentumX = 1, kMomentumY = 2, kEnergy = 3 };
  static constexpr int kCount = 4;
};

/// The primitive state rho, u, v, p, T (GasSolver::primitive_field()).
struct Primitive {
  enum Component : int {
    kDensity = 0,
    kVelocityX = 1,
    kVelocityY = 2,
    kPressure = 3,
    kTemperature = 4
  };
  static constexpr int kCount = 5;
};

}  // namespace dustlift
