#pragma once
// The gas-particle effects a scene switches on, built once from its [coupling] section, in
// Table 1's order (an effect that is off is not in the list and runs no code). The list decides
// everything downstream: which derived gas fields the coupling makes (what the effects read),
// the columns on the parcels, the DEM's forced sub-step (the effects' functors composed into
// one loop, forced_euler.hpp) and the force parts the outputs write.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/parcel_forcing.hpp"

namespace dustlift {

struct CouplingConfig;

class CouplingEffects {
 public:
  explicit CouplingEffects(const CouplingConfig& c);
  ~CouplingEffects();
  CouplingEffects(CouplingEffects&&) noexcept;
  CouplingEffects& operator=(CouplingEffects&&) noexcept;

  bool empty() const { return effects_.empty(); }
  /// What the active effects read beyond the gas state (the fields to make).
  const GasReads& reads() const { return reads_; }
  /// One line per active effect, for `dustlift info`.
  std::vector<std::string> descriptions() const;
  /// Where the flow leaves an active effect's range of validity (info).
  std::vector<std::string> validity(const FlowEnvelope& e) const;
  /// Attaches every active effect's columns.
  void attach(ParcelTable& table);
  /// Every effect's coefficients for parcels [k0, k0 + n) (one virtual call per effect).
  void coefficients(const ModelInput* in, std::size_t k0, std::size_t n, ParcelTable& t,
                    const StepContext& step) const {
    for (const auto& e : effects_) e->coefficients(in, k0, n, t, step);
  }
  /// The coefficients the implicit exchange scales (none when no effect exchanges that;
  /// known after attach).
  const std::vector<StiffCoefficient>& stiff_momentum() const { return stiff_momentum_; }
  const std::vector<StiffCoefficient>& stiff_heat() const { return stiff_heat_; }

  /// The columns a sub-step reads besides the effects' own: the frozen gas and the exchange sums.
  struct SubstepColumns {
    ParcelColumn gas_u, gas_v, gas_rotation, gas_temperature;
    ParcelColumn impulse_x, impulse_y, work, heat;
    ParcelColumn relative_rotation;  ///< Omega_g - w of the last sub-step (written when stored)
  };
  /// The DEM's forcing: the active effects' sub-step functors in one fused loop (after attach).
  std::shared_ptr<const ParcelForcing> forcing(const SubstepColumns& columns) const;

 private:
  std::vector<std::unique_ptr<CouplingEffect>> effects_;
  GasReads reads_;
  std::vector<StiffCoefficient> stiff_momentum_, stiff_heat_;
};

}  // namespace dustlift
