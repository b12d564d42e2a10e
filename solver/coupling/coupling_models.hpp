#pragma once
// The gas-particle effects of the paper's Table 1 and eqs. (7)-(10) as a list of models built
// once from the scene (an effect that is off is not in the list and costs nothing). The list
// decides everything downstream: which derived gas fields the coupling makes (what the models
// read), which sub-step effects the DEM's forced kernel runs and which force parts the outputs
// write (what they write). Once per CFD step each model turns the gas sampled at a parcel into
// the coefficient of its sub-step law (models/coupling_model.hpp):
//   drag      K      F_drag = K u_r               (Clift-Gauvin x Parmar xi_1 x Sangani xi_2)
//   Magnus    M      F_Magnus = M w_r z x u_r     (+-C_LM (pi/8) rho d^3, optional Lun-Liu factor)
//   pressure  F_p    -V_p grad p
//   torque    kappa  M_rotation = kappa w_r       (Dennis et al., slope at the step's w_r)
//   heat      H      Q = H (T_g - T_p)            (Ranz-Marshall)
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/models/coupling_model.hpp"

namespace dustlift {

class CouplingModels {
 public:
  /// The active models of `c`, in Table 1's order.
  explicit CouplingModels(const CouplingConfig& c);

  /// What the active models read beyond the gas state (the fields to make).
  const GasReads& reads() const { return reads_; }
  /// The force parts they write (the sub-step effects, the outputs' force parts).
  const ForceParts& writes() const { return writes_; }
  /// One line per active model, for `dustlift info`.
  std::vector<std::string> descriptions() const;
  /// Every model's coefficients for n parcels (one virtual call per model and batch).
  void coefficients(const ModelInput* in, SubstepCoefficients* out, std::size_t n) const {
    for (const auto& m : models_) m->coefficients(in, out, n);
  }

 private:
  std::vector<std::unique_ptr<CouplingModel>> models_;
  GasReads reads_;
  ForceParts writes_;
};

}  // namespace dustlift
