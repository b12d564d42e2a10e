#pragma once
// The build's contact units in the order the contact pass adds their forces (their kPosition),
// for the DEM's own sources (the list is generated into the dem library's private include
// path). Outside the DEM, contact_summary.hpp names and describes them.
#include <cstddef>
#include <tuple>

#include "solver/core/unit_order.hpp"
#include "solver/dem/contact_effects/contact_units.hpp"
#include "solver/dem/dem_config.hpp"

namespace dustlift {

/// Every contact unit, ordered by kPosition. A new contact effect is its unit: the build lists
/// every unit (contact_units.hpp).
using OrderedContactUnits = decltype(ordered(ContactUnits{}));
template <class... U>
std::tuple<U...> as_tuple(ContactTypeList<U...>);
using OrderedContactTuple = decltype(as_tuple(OrderedContactUnits{}));

/// Calls f with a null pointer of each unit type U in order (for its static members).
template <class F, class... U>
void for_each_contact_unit(ContactTypeList<U...>, F&& f) {
  (f(static_cast<const U*>(nullptr)), ...);
}
template <class F>
void for_each_contact_unit(F&& f) {
  for_each_contact_unit(OrderedContactUnits{}, f);
}

/// Calls run(units...) with the scene's active units, made from its config, in order: one
/// instantiation per combination of active units, so a unit that is off runs no code.
template <std::size_t K = 0, class Run, class... On>
void with_active_contact_units(const DemConfig& c, Run&& run, const On&... on) {
  if constexpr (K == std::tuple_size_v<OrderedContactTuple>) {
    run(on...);
  } else {
    using U = std::tuple_element_t<K, OrderedContactTuple>;
    if (U::active(c))
      with_active_contact_units<K + 1>(c, run, on..., U(c));
    else
      with_active_contact_units<K + 1>(c, run, on...);
  }
}

}  // namespace dustlift
