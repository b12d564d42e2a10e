#include "solver/coupling/effects/effect_list.hpp"

#include <algorithm>
#include <array>
#include <tuple>
#include <utility>

#include "solver/core/unit_order.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect_units.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {
namespace {

/// Every effect unit in the order the sub-step applies them (their kPosition: Table 1's). A new
/// effect is its unit: the build lists every unit (effect_units.hpp).
using SubstepEffectTypes = decltype(ordered(EffectUnits{}));

/// The scene's active effects, in sub-step order (which is also the order of their columns).
template <class... E>
void make_active(EffectTypeList<E...>, const CouplingConfig& c,
                 std::vector<std::unique_ptr<CouplingEffect>>& effects) {
  ((E::active(c) ? effects.push_back(std::make_unique<E>(c)) : void()), ...);
}

/// Writes Omega_g - w of the parcel when the force parts are stored (band filters read it).
struct RelativeRotation : SubstepRoles, StoresValue {
  const double* rotation;
  double force(std::size_t i, SubstepParcel& p) const { return rotation[i] - p.omega; }
};

/// The active effects' functors composed into forced_euler: one instantiation per combination
/// of active effects, chosen by walking the types once per sub-step.
template <class... All>
class ComposedForcing final : public ParcelForcing {
 public:
  ComposedForcing(std::array<const CouplingEffect*, sizeof...(All)> active,
                  const CouplingEffects::SubstepColumns& c)
      : active_(active), c_(c) {}

  double substep(ParcelSystem& ps, std::size_t n, double dt, bool store) const override {
    EulerArrays a = ps.euler_arrays();
    a.impulse_x = ps.column(c_.impulse_x).data();
    a.impulse_y = ps.column(c_.impulse_y).data();
    a.work = ps.column(c_.work).data();
    a.heat = ps.column(c_.heat).data();
    const FrozenGas gas{ps.column(c_.gas_u).data(), ps.column(c_.gas_v).data(),
                        ps.column(c_.gas_rotation).data(), ps.column(c_.gas_temperature).data()};
    const RelativeRotation rotation{{}, {ps.column(c_.relative_rotation).data()}, gas.rotation};
    return run<0>(ps, a, gas, n, dt, store, rotation);
  }

 private:
  template <std::size_t K, class... F>
  double run(ParcelSystem& ps, const EulerArrays& a, const FrozenGas& gas, std::size_t n, double dt,
             bool store, const F&... functors) const {
    if constexpr (K == sizeof...(All)) {
      return store ? forced_euler<true>(a, n, dt, functors...)
                   : forced_euler<false>(a, n, dt, functors...);
    } else {
      using E = std::tuple_element_t<K, std::tuple<All...>>;
      if (active_[K] == nullptr) return run<K + 1>(ps, a, gas, n, dt, store, functors...);
      const auto& e = static_cast<const E&>(*active_[K]);
      return run<K + 1>(ps, a, gas, n, dt, store, functors..., e.substep(ps, gas));
    }
  }

  std::array<const CouplingEffect*, sizeof...(All)> active_;
  CouplingEffects::SubstepColumns c_;
};

template <class... All>
std::shared_ptr<const ParcelForcing> compose(
    EffectTypeList<All...>, const std::vector<std::unique_ptr<CouplingEffect>>& effects,
    const CouplingEffects::SubstepColumns& columns) {
  std::array<const CouplingEffect*, sizeof...(All)> active{};
  std::size_t k = 0;
  // Each effect type in the list takes its instance, if the scene made one.
  ((active[k++] = [&]() -> const CouplingEffect* {
     for (const auto& e : effects)
       if (dynamic_cast<const All*>(e.get()) != nullptr) return e.get();
     return nullptr;
   }()),
   ...);
  return std::make_shared<ComposedForcing<All...>>(active, columns);
}

}  // namespace

CouplingEffects::CouplingEffects(const CouplingConfig& c) {
  make_active(SubstepEffectTypes{}, c, effects_);
  for (const auto& e : effects_) reads_ |= e->reads();
}

CouplingEffects::~CouplingEffects() = default;
CouplingEffects::CouplingEffects(CouplingEffects&&) noexcept = default;
CouplingEffects& CouplingEffects::operator=(CouplingEffects&&) noexcept = default;

std::vector<std::string> CouplingEffects::descriptions() const {
  std::vector<std::string> d;
  for (const auto& e : effects_) d.push_back(e->description());
  return d;
}

std::vector<std::string> CouplingEffects::validity(const FlowEnvelope& envelope) const {
  std::vector<std::string> lines;
  for (const auto& e : effects_) {
    for (std::string& l : e->validity(envelope)) lines.push_back(std::move(l));
  }
  return lines;
}

void CouplingEffects::attach(ParcelTable& table) {
  stiff_momentum_.clear();
  stiff_heat_.clear();
  for (const auto& e : effects_) {
    e->attach(table);
    if (const auto c = e->stiff_momentum()) stiff_momentum_.push_back(*c);
    if (const auto c = e->stiff_heat()) stiff_heat_.push_back(*c);
  }
}

std::shared_ptr<const ParcelForcing> CouplingEffects::forcing(const SubstepColumns& c) const {
  return compose(SubstepEffectTypes{}, effects_, c);
}

}  // namespace dustlift
