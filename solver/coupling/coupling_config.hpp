#pragma once
// Which gas-particle effects act, and their model options (paper Table 1, eqs. 7-16).
// Every effect that is off costs nothing: no loop runs and no field is computed for it.
#include "solver/coupling/grid_transfer.hpp"
#include "solver/laws/added_mass.hpp"
#include "solver/laws/drag.hpp"
#include "solver/laws/magnus.hpp"

namespace dustlift {

struct CouplingConfig {
  /// The gas feels the particles (porosity alpha_g and exchange terms f_p, s_p, q_p).
  /// Off: one-way coupling, particles are carried by a gas that does not see them.
  bool two_way = true;
  bool drag = true;
  bool compressibility_correction = true;  ///< xi_1 (Parmar et al. 2010)
  aero::VolumeFractionCorrection
      volume_fraction{};  ///< xi_2 (Sangani et al. 1991) or Tenneti et al. (2011)
  bool magnus = true;
  double magnus_coefficient = 1.0;  ///< C_LM (paper section 3.2: 1.0)
  aero::MagnusConvention magnus_convention = aero::MagnusConvention::Paper;
  bool lun_liu = false;  ///< Re-dependent factor on C_LM
  bool pressure_force = true;
  /// Inviscid-unsteady (added-mass) force (Parmar et al. 2008); off by default (the paper
  /// leaves it out).
  bool added_mass = false;
  aero::AddedMassVolumeFraction added_mass_volume_fraction = aero::AddedMassVolumeFraction::Beguin;
  /// D(rho u)/Dt of the added mass's fluid part: the resolved gas's, or -grad p.
  aero::FluidAcceleration added_mass_fluid_acceleration = aero::FluidAcceleration::Resolved;
  bool rotation_torque = true;  ///< Dennis et al. (1980) friction torque
  double torque_stokes_below =
      0.0;  ///< Re_w below which Stokes' torque is used (0: fit only, as the paper)
  bool heat_transfer = true;  ///< Ranz-Marshall (eqs. 7-10)
  InterpolationRule interpolation = InterpolationRule::Triangle;
  /// The pressure-gradient force and the added mass's fluid part from the undisturbed flow
  /// averaged over the particle's volume (their Faxen form), not its centre value: for
  /// particles larger than the cells.
  bool finite_size = false;
  /// Side of the square over which a parcel deposits (Table 2 "domain of influence
  /// diameter", 100 um); 0 deposits into the cell holding the centre (eq. 12 literally).
  double influence_width = 100e-6;
  /// alpha_p is capped here in the gas's porosity (a packed cell cannot leave no room for gas).
  double max_volume_fraction = 0.9;
};

}  // namespace dustlift
