#pragma once
// A gas-particle effect as one unit (paper Table 1, eqs. 7-10, and the closures beyond the
// paper). Its unit declares, in one place:
//   - the columns it keeps per parcel (its coefficients and its force part), attached to the
//     parcel table when the coupling starts;
//   - its coefficient, computed once per CFD step from the gas sampled at each parcel
//     (coefficients(), one virtual call per batch of parcels);
//   - its sub-step functor (`Substep`, made by `substep()`), which the DEM's forced Euler step
//     applies to the parcel's current slip, spin or temperature in the frozen gas
//     (solver/dem/forced_euler.hpp says what a functor may add);
//   - what it reads beyond the sampled gas, its line for `dustlift info`, and where a scene
//     leaves the law's range of validity.
// The laws themselves are stateless functions in solver/laws/, shared with the tests: the
// coefficient times the sub-step piece is the published law at the sampled state. The parcel's
// share is n_i times the per-particle value (eqs. 13-15).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "solver/dem/parcel_table.hpp"

namespace dustlift {

/// Gas interpolated to a parcel (eq. 16) with the derived fields the effects read.
struct GasSample {
  double rho = 1.0, u = 0.0, v = 0.0, p = 0.0, T = 300.0;
  double mu = 1.8e-5, lambda = 0.026, c = 340.0, cp = 1005.0, gamma = 1.4;
  double alpha_g = 1.0;
  double vorticity = 0.0;  ///< omega_z = dv/dx - du/dy
  double dpdx = 0.0, dpdy = 0.0;
  /// grad(rho u) and grad(rho v), the gas momentum's gradient
  double dx_rho_u = 0.0, dy_rho_u = 0.0, dx_rho_v = 0.0, dy_rho_v = 0.0;
  /// The gas momentum at the parcel: rho u, rho v (their averages over the particle with
  /// coupling.finite_size)
  double rho_u = 0.0, rho_v = 0.0;
};

/// The parcel seen by the effects at the start of the CFD step.
struct ParcelAtSample {
  double vx = 0.0, vy = 0.0, omega = 0.0;  ///< m/s, rad/s (counter-clockwise)
  double diameter = 100e-6;                ///< m, of a real particle
  double mass = 0.0;                       ///< kg, of a real particle
};

/// What the effects read of one parcel: its gas, itself, slip = |u_g - v_p| and
/// re = rho slip d / mu.
struct ModelInput {
  GasSample gas;
  ParcelAtSample parcel;
  double slip = 0.0, re = 0.0;
};

/// What an effect reads beyond the gas state at the parcel (rho, u, v, p, T, the properties
/// at T and alpha_g, which are always sampled). A field nobody reads is not made.
struct GasReads {
  bool rotation = false;           ///< omega_z / 2 at the parcel (the vorticity field)
  bool pressure_gradient = false;  ///< grad p at the parcel (its field)
  bool momentum_gradient = false;  ///< grad(rho u), grad(rho v) at the parcel (their fields)
  GasReads& operator|=(const GasReads& o) {
    rotation = rotation || o.rotation;
    pressure_gradient = pressure_gradient || o.pressure_gradient;
    momentum_gradient = momentum_gradient || o.momentum_gradient;
    return *this;
  }
};

/// The gas sampled at each parcel at the step's start, as the sub-step functors read it (the
/// coupling's columns: velocity, rotation omega_z / 2 and temperature).
struct FrozenGas {
  const double *u, *v, *rotation, *temperature;
};

/// A coefficient of an exchange that can be stiff (the implicit exchange scales it): the column
/// as sampled and the column the sub-steps apply.
struct StiffCoefficient {
  ParcelColumn sampled, applied;
};

/// What a CFD step's sampling knows besides the samples.
struct StepContext {
  double time = 0.0;  ///< s, at the step's start
};

/// What `dustlift info` knows of the flow a scene makes, to say where an effect's law leaves
/// the range it was fitted in.
struct FlowEnvelope {
  double max_volume_fraction = 0.0;  ///< the densest packing of the particles (the layer's)
  double max_reynolds = 0.0;         ///< particle Reynolds number of a particle at rest in the
                                     ///< post-shock gas
  double max_mach = 0.0;             ///< slip Mach number of that particle
};

class CouplingEffect {
 public:
  virtual ~CouplingEffect() = default;
  /// One line for `dustlift info` and run.log.
  virtual std::string description() const = 0;
  virtual GasReads reads() const { return {}; }
  /// Attaches the effect's columns to the parcel table (once, when the coupling starts).
  virtual void attach(ParcelTable& table) = 0;
  /// The coefficients of parcels [k0, k0 + n), whose samples are in[0 .. n).
  virtual void coefficients(const ModelInput* in, std::size_t k0, std::size_t n, ParcelTable& table,
                            const StepContext& step) const = 0;
  /// The momentum or heat exchange coefficient the implicit exchange scales, if any.
  virtual std::optional<StiffCoefficient> stiff_momentum() const { return std::nullopt; }
  virtual std::optional<StiffCoefficient> stiff_heat() const { return std::nullopt; }
  /// Where the flow leaves the range the law was fitted or derived in (one line each).
  virtual std::vector<std::string> validity(const FlowEnvelope&) const { return {}; }
};

/// The two columns of a stiff exchange coefficient (drag's, the heat transfer's): as sampled
/// (kept in checkpoints: the implicit exchange sums every parcel of a cell, resting ones too)
/// and as the sub-steps apply it.
class StiffColumns {
 public:
  struct Columns {
    double *sampled, *applied;
  };
  Columns columns(ParcelTable& t) const {
    return {t.column(sampled_).data(), t.column(applied_).data()};
  }

 protected:
  void attach_stiff(ParcelTable& t, const char* name, const char* unit) {
    sampled_ = t.attach_column({std::string(name) + "_sampled", unit, true, false});
    applied_ = t.attach_column({name, unit, false, false});
  }
  StiffCoefficient stiff() const { return {sampled_, applied_}; }
  ParcelColumn sampled_, applied_;
};

/// The batch loop over an effect's per-parcel `coefficient(const ModelInput&, std::size_t k,
/// Columns&)`, with its columns resolved once per batch by `Model::columns(table)`.
template <class Model>
class BatchedEffect : public CouplingEffect {
 public:
  void coefficients(const ModelInput* in, std::size_t k0, std::size_t n, ParcelTable& table,
                    const StepContext&) const final {
    const Model& m = static_cast<const Model&>(*this);
    auto out = m.columns(table);
    for (std::size_t q = 0; q < n; ++q) m.coefficient(in[q], k0 + q, out);
  }
};

/// Column helpers for the effects' attach().
namespace effect_columns {
/// A coefficient made every CFD step (not kept in checkpoints).
inline ParcelColumn coefficient(ParcelTable& t, const char* name, const char* unit) {
  return t.attach_column({name, unit, false, false});
}
/// A column a later step reads for parcels it does not sample again: kept in checkpoints.
inline ParcelColumn carried(ParcelTable& t, const char* name, const char* unit) {
  return t.attach_column({name, unit, true, false});
}
/// A force part, per real particle: kept in checkpoints (resting parcels keep it) under
/// `checkpoint` ("" = parcels/attached_<name>), written as the point array `written_as`
/// component `component` ("" = not written), tagged with `part`.
inline ParcelColumn part(ParcelTable& t, const char* name, const char* unit, ForcePart part,
                         const char* written_as, int component, const char* checkpoint) {
  ParcelColumnSpec spec{name, unit, true, *written_as != '\0'};
  spec.checkpoint_name = checkpoint;
  spec.written_as = written_as;
  spec.component = component;
  spec.part = part;
  return t.attach_column(std::move(spec));
}
}  // namespace effect_columns

}  // namespace dustlift
