#pragma once
// Settings of the gas solver, as resolved from a scene (all SI units).
#include <limits>
#include <string>

namespace dustlift {

enum class ThermoModel { CaloricallyPerfect, ThermallyPerfect };
enum class TransportModel { Inviscid, Constant, Sutherland, GordonWilke };
enum class Reconstruction { FirstOrder, Muscl2, Muscl3 };
enum class Limiter { Minmod, VanAlbada };
enum class BoundaryKind { SlipWall, NoSlipWall, Inflow, Outflow, Periodic };

/// A gas state in primitive variables.
struct PrimitiveState {
  double rho = 1.0;  ///< kg/m^3
  double u = 0.0;    ///< m/s
  double v = 0.0;    ///< m/s
  double p = 1.0;    ///< Pa
  /// K: the temperature as given (a scene's `T`), kept exactly; NaN: p / (rho R).
  double T = std::numeric_limits<double>::quiet_NaN();
};

/// T of a state: as given, else from p = rho R T (eq. 4, both thermodynamic models).
inline double temperature_of(const PrimitiveState& s, double gas_constant) {
  return s.T == s.T ? s.T : s.p / (s.rho * gas_constant);
}

struct ThermoConfig {
  ThermoModel model = ThermoModel::ThermallyPerfect;
  double gamma = 1.4;              ///< calorically perfect only
  double gas_constant = 288.190;   ///< J/(kg K); air O2:N2 = 1:3.76 (docs/gas-solver.md)
};

struct TransportConfig {
  TransportModel model = TransportModel::GordonWilke;
  double viscosity = 1.85031e-5;   ///< Pa s, Constant model (air at 300 K)
  double prandtl = 0.713;          ///< Constant and Sutherland: lambda = mu cp / Pr
  double sutherland_mu_ref = 1.716e-5;  ///< Pa s at sutherland_t_ref
  double sutherland_t_ref = 273.15;     ///< K
  double sutherland_s = 110.4;          ///< K
};

struct SchemeConfig {
  Reconstruction reconstruction = Reconstruction::Muscl3;
  Limiter limiter = Limiter::Minmod;
  double minmod_b = 2.0;   ///< compression parameter, 1 <= b <= (3 - kappa)/(1 - kappa)
  double cfl = 0.5;        ///< nu_CFD of eq. (17)
};

struct BoundaryConfig {
  BoundaryKind left = BoundaryKind::Outflow;
  BoundaryKind right = BoundaryKind::Outflow;
  BoundaryKind bottom = BoundaryKind::SlipWall;
  BoundaryKind top = BoundaryKind::SlipWall;
  /// State imposed at Inflow boundaries. When the scene gives none, the initial
  /// condition's state next to that boundary is used (e.g. the post-shock state).
  PrimitiveState inflow{};
  bool inflow_given = false;
};

struct GasConfig {
  ThermoConfig thermo;
  TransportConfig transport;
  SchemeConfig scheme;
  BoundaryConfig boundary;
  /// Skip cells whose whole stencil rests at one state with no source: exact (the update
  /// would change no bit), set from the scene's run.skip_at_rest.
  bool skip_resting_cells = true;
  /// 0: "at rest" means exactly (the default). > 0: within this relative tolerance of the
  /// resting reference (rest_ranges.hpp), which also skips the rounding noise that runs ahead
  /// of a shock; changes results at that level (run.rest_tolerance, docs/performance.md).
  double rest_tolerance = 0.0;
  /// m/s^2, gravity on the gas (scene gas.gravity = [g_x, g_y]): the body force a rho g in
  /// the momenta and a rho g.u in the energy. Nonzero turns skipping off (no state rests).
  double gravity_x = 0.0;
  double gravity_y = 0.0;
  bool has_gravity() const { return gravity_x != 0.0 || gravity_y != 0.0; }
};

/// Initial condition of the gas.
struct InitialCondition {
  enum class Kind { Uniform, Riemann, Shock };
  Kind kind = Kind::Uniform;
  PrimitiveState state{};        ///< Uniform; for Shock: the quiescent pre-shock state
  PrimitiveState left{}, right{};///< Riemann: states below/above `position`
  char axis = 'x';               ///< Riemann/Shock: normal direction of the split
  double position = 0.0;         ///< m, split / shock location
  double mach = 1.44;            ///< Shock: shock Mach number into `state` (moving towards +axis)
};

}  // namespace dustlift
