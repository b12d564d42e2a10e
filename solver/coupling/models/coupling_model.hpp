#pragma once
// What a gas-particle coupling model is (the paper's Table 1 and eqs. 7-10). Each model owns
// its whole law, in one header per model (drag.hpp, magnus.hpp, pressure_force.hpp,
// rotation_torque.hpp, heat_transfer.hpp):
//   - the published law per REAL particle (aero::, what the literature states);
//   - the coefficient the coupling computes once per CFD step from the gas sampled at each
//     parcel (coefficient(), through the batch interface below);
//   - the sub-step piece the DEM's forced kernel applies to the parcel's current slip, spin or
//     temperature in the frozen gas (static inline functions the DEM calls);
//   - what it reads beyond the sampled gas and which force parts it writes (kTraits).
// The coefficient times the sub-step piece is the published law at the sampled state; the
// tests check that with the functions the coupling and the DEM run. The parcel's share is
// n_i times the per-particle value (eqs. 13-15).
#include <cstddef>
#include <string>

#include "solver/dem/parcel_table.hpp"

namespace dustlift {

/// Gas interpolated to a parcel (eq. 16) with the derived fields the models need.
struct GasSample {
  double rho = 1.0, u = 0.0, v = 0.0, p = 0.0, T = 300.0;
  double mu = 1.8e-5, lambda = 0.026, c = 340.0, cp = 1005.0;
  double alpha_g = 1.0;
  double vorticity = 0.0;  ///< omega_z = dv/dx - du/dy
  double dpdx = 0.0, dpdy = 0.0;
};

/// The parcel seen by the models at the start of the CFD step.
struct ParcelAtSample {
  double vx = 0.0, vy = 0.0, omega = 0.0;  ///< m/s, rad/s (counter-clockwise)
  double diameter = 100e-6;                ///< m, of a real particle
  double mass = 0.0;                       ///< kg, of a real particle
};

/// The sub-step coefficients of one parcel (zero for effects that are off).
struct SubstepCoefficients {
  double drag = 0.0;                                ///< K, N s/m
  double magnus = 0.0;                              ///< M (with the convention's sign), N s^2/m^2
  double pressure_fx = 0.0, pressure_fy = 0.0;      ///< N
  double torque = 0.0;                              ///< kappa, N m s
  double heat = 0.0;                                ///< H, W/K
  double added_mass = 0.0;                          ///< m_a = C_M rho_g V_p, kg
  double added_mass_fx = 0.0, added_mass_fy = 0.0;  ///< C_M V_p (-grad p), N
  double inv_total_mass = 0.0;                      ///< 1 / (m + m_a), 1/kg
};

/// What the models read of one parcel: its gas, itself, slip = |u_g - v_p| and
/// re = rho slip d / mu.
struct ModelInput {
  GasSample gas;
  ParcelAtSample parcel;
  double slip = 0.0, re = 0.0;
};

/// What a model reads beyond the gas state at the parcel (rho, u, v, p, T, the properties
/// at T and alpha_g, which are always sampled). A field nobody reads is not made.
struct GasReads {
  bool rotation = false;           ///< omega_z / 2 at the parcel (the vorticity field)
  bool pressure_gradient = false;  ///< grad p at the parcel (its field)
  bool temperature = false;        ///< T_g over the sub-steps
  GasReads& operator|=(const GasReads& o) {
    rotation = rotation || o.rotation;
    pressure_gradient = pressure_gradient || o.pressure_gradient;
    temperature = temperature || o.temperature;
    return *this;
  }
};

/// The parts of the gas forcing a model writes: the sub-step effects the DEM runs
/// (GasForcing) and the parcel's force-part columns the outputs write (ParcelSystem).
struct ForceParts {
  bool drag = false, magnus = false, pressure = false, torque = false, heat = false;
  bool added_mass = false;
  /// Whether the part that the parcel table's columns tagged `part` hold is written (contact
  /// is always computed).
  bool has(ForcePart part) const {
    switch (part) {
      case ForcePart::Drag:
        return drag;
      case ForcePart::Magnus:
        return magnus;
      case ForcePart::Pressure:
        return pressure;
      case ForcePart::FluidTorque:
        return torque;
      case ForcePart::Heat:
        return heat;
      case ForcePart::AddedMass:
        return added_mass;
      default:
        return true;
    }
  }
  ForceParts& operator|=(const ForceParts& o) {
    drag = drag || o.drag;
    magnus = magnus || o.magnus;
    pressure = pressure || o.pressure;
    torque = torque || o.torque;
    heat = heat || o.heat;
    added_mass = added_mass || o.added_mass;
    return *this;
  }
};

struct ModelTraits {
  GasReads reads;
  ForceParts writes;
};

class CouplingModel {
 public:
  virtual ~CouplingModel() = default;
  /// One line for `dustlift info`.
  virtual std::string description() const = 0;
  virtual ModelTraits traits() const = 0;
  /// Sets this model's coefficient for each of n parcels: one virtual call per batch, the
  /// per-parcel formula (coefficient() of the model) inlined in its loop.
  virtual void coefficients(const ModelInput* in, SubstepCoefficients* out,
                            std::size_t n) const = 0;
};

/// The batch loop over a model's per-parcel `coefficient(const ModelInput&,
/// SubstepCoefficients&)`, and its traits from `Model::kTraits`.
template <class Model>
class BatchedCouplingModel : public CouplingModel {
 public:
  ModelTraits traits() const final { return Model::kTraits; }
  void coefficients(const ModelInput* in, SubstepCoefficients* out, std::size_t n) const final {
    const Model& m = static_cast<const Model&>(*this);
    for (std::size_t k = 0; k < n; ++k) m.coefficient(in[k], out[k]);
  }
};

}  // namespace dustlift
