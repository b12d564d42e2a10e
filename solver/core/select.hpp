#pragma once
// min and clamp by value, with the results of std::min and std::clamp: the std versions
// return references, which keeps GCC from vectorising loops that use them on
// loaded values (grid_transfer.hpp, AxisView::locate_bounded).

namespace dustlift {

template <class T>
constexpr T min_of(T a, T b) { return b < a ? b : a; }
template <class T>
constexpr T clamp_of(T v, T lo, T hi) { return v < lo ? lo : (hi < v ? hi : v); }

}  // namespace dustlift
