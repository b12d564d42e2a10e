#pragma once
// The order of a build's units (the coupling's effects, the DEM's contact effects): each unit
// type declares its kPosition, and a list of them is sorted by it at compile time, so that the
// build may list them in any order (by their headers' names).
#include <algorithm>
#include <array>
#include <cstddef>
#include <tuple>
#include <utility>

namespace dustlift {

/// The units' indices in their list, ordered by their kPosition.
template <class... E>
constexpr std::array<std::size_t, sizeof...(E)> by_position() {
  constexpr std::array<int, sizeof...(E)> position{E::kPosition...};
  std::array<std::size_t, sizeof...(E)> order{};
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return position[a] < position[b]; });
  return order;
}

template <class... E>
constexpr bool distinct_positions() {
  constexpr std::array<int, sizeof...(E)> position{E::kPosition...};
  for (std::size_t a = 0; a < position.size(); ++a)
    for (std::size_t b = a + 1; b < position.size(); ++b)
      if (position[a] == position[b]) return false;
  return true;
}

template <class List, class Indices>
struct OrderedUnits;
template <template <class...> class List, class... E, std::size_t... I>
struct OrderedUnits<List<E...>, std::index_sequence<I...>> {
  static_assert(distinct_positions<E...>(), "two units share a kPosition");
  static constexpr auto order = by_position<E...>();
  using type = List<std::tuple_element_t<order[I], std::tuple<E...>>...>;
};

/// The list type List<E...> with its units sorted by kPosition (use in decltype).
template <template <class...> class List, class... E>
auto ordered(List<E...>) -> typename OrderedUnits<List<E...>, std::index_sequence_for<E...>>::type;

}  // namespace dustlift
