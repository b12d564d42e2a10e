#pragma once
// A 2-D vector (x horizontal, y vertical); z is out of plane, right-handed.
#include <cmath>

namespace dustlift {

struct Vec2 {
  double x = 0.0, y = 0.0;
  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator*(double s) const { return {x * s, y * s}; }
  constexpr Vec2& operator+=(Vec2 o) { x += o.x; y += o.y; return *this; }
  constexpr double dot(Vec2 o) const { return x * o.x + y * o.y; }
  double norm() const { return std::hypot(x, y); }
};
constexpr Vec2 operator*(double s, Vec2 v) { return v * s; }
/// z-component of a x b.
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// (w z-hat) x a for a scalar out-of-plane w.
constexpr Vec2 cross(double w, Vec2 a) { return {-w * a.y, w * a.x}; }

}  // namespace dustlift
