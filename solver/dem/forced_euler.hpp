#pragma once
// The DEM's symplectic Euler sub-step (paper Sect. 2.3: v^{n+1} = v^n + dt F^n / m,
// x^{n+1} = x^n + dt v^{n+1}) under contacts, gravity and a pack of forcing effects, fused
// into one loop over the parcels. An effect is a small functor that adds its part at fixed
// points of the loop; one that is not in the pack runs no code. Per REAL particle throughout.
//
// An effect E provides (each member but Part optional, found by `requires`):
//   using Part = ...;                                      what it stores (Vec2, double, ...)
//   static constexpr bool kExchanges, kLocal, kTorque, kHeat, kInertia   what it adds
//   Part force(std::size_t i, SubstepParcel& p) const      adds to p's exchanged or local
//                                                          force, torque or heat; returns its part
//   Vec2 acceleration(std::size_t i, const SubstepParcel& p, Vec2 force, Vec2 gravity) const
//                      kInertia only (at most one effect): the sub-step's acceleration under
//                      the total force of the others (an added mass changes the inertia)
//   Part after(std::size_t i, SubstepParcel& p) const      sees the new velocity and
//                                                          acceleration (p.ax, p.ay)
//   void store(std::size_t i, const Part& part) const      writes its force part (the last
//                                                          sub-step of a CFD step)
// A part is computed once and stored as it was applied.
// Forces exchanged with the gas are summed per parcel into the exchange sums (impulse, and
// work with the sub-step's mean velocity: exactly the kinetic energy symplectic Euler gives).
#include <algorithm>
#include <cstddef>
#include <utility>

#include "solver/core/parallel_minimum.hpp"
#include "solver/core/vec2.hpp"

namespace dustlift {

/// One parcel during one forced sub-step. The sums start at -0, the exact identity of
/// addition (x + -0 = x for every x, -0 included): the first part added is taken as it is, so
/// a sum holds the same bits however many effects add to it.
struct SubstepParcel {
  double vx, vy, omega, temperature;              ///< at the sub-step's start
  double inv_mass;                                ///< 1/m of one real particle
  double exchanged_x = -0.0, exchanged_y = -0.0;  ///< forces exchanged with the gas, N
  double local_x = -0.0, local_y = -0.0;          ///< forces not exchanged, N
  double torque = -0.0;                           ///< torque besides contacts, N m
  double heat = -0.0;                             ///< heat flow into the particle, W
  double vx_new = 0.0, vy_new = 0.0;              ///< after the velocity update
  double ax = 0.0, ay = 0.0;                      ///< the sub-step's acceleration (kInertia)
};

/// The roles a functor takes (what it adds); a functor derives from this and sets its own.
struct SubstepRoles {
  static constexpr bool kExchanges = false, kLocal = false, kTorque = false, kHeat = false,
                        kInertia = false;
};

/// A functor whose part is a force stored in two columns.
struct StoresForce {
  using Part = Vec2;
  double *fx, *fy;
  void store(std::size_t i, Vec2 f) const {
    fx[i] = f.x;
    fy[i] = f.y;
  }
};

/// A functor whose part is one value per parcel (a torque, a heat flow) stored in a column.
struct StoresValue {
  using Part = double;
  double* out;
  void store(std::size_t i, double v) const { out[i] = v; }
};

/// The parcel columns a forced sub-step reads and writes (ParcelSystem::euler_arrays), and
/// the exchange sums of the forcing (null when it exchanges nothing).
struct EulerArrays {
  double *x, *y, *vx, *vy, *omega, *temperature;
  const double *inv_mass, *inv_inertia, *contact_fx, *contact_fy, *contact_torque, *x_build,
      *y_build, *inv_skin2;
  double gravity_x, gravity_y, inv_heat_capacity;
  double *impulse_x = nullptr, *impulse_y = nullptr, *work = nullptr, *heat = nullptr;
};

namespace forced_euler_detail {
/// The effects' parts of one parcel: a plain aggregate (a std::tuple inside the OpenMP simd
/// loop stops GCC 12).
template <class... T>
struct Parts {};
template <class T, class... R>
struct Parts<T, R...> {
  T head{};
  Parts<R...> tail{};
};
template <std::size_t K, class T, class... R>
auto& get(Parts<T, R...>& p) {
  if constexpr (K == 0) {
    return p.head;
  } else {
    return get<K - 1>(p.tail);
  }
}

template <class E>
void force(const E& e, std::size_t i, SubstepParcel& p, typename E::Part& part) {
  if constexpr (requires { e.force(i, p); }) part = e.force(i, p);
}
template <class E>
void after(const E& e, std::size_t i, SubstepParcel& p, typename E::Part& part) {
  if constexpr (requires { e.after(i, p); }) part = e.after(i, p);
}
template <class E>
void store(const E& e, std::size_t i, const typename E::Part& part) {
  if constexpr (requires { e.store(i, part); }) e.store(i, part);
}
template <class E>
void accelerate(const E& e, std::size_t i, SubstepParcel& p, Vec2 f, Vec2 g) {
  if constexpr (E::kInertia) {
    const Vec2 a = e.acceleration(i, p, f, g);
    p.ax = a.x;
    p.ay = a.y;
  }
}

/// What a pack of effects adds, taken together.
template <class... E>
struct PackRoles {
  static constexpr bool kExchanges = (false || ... || E::kExchanges);
  static constexpr bool kLocal = (false || ... || E::kLocal);
  static constexpr bool kTorque = (false || ... || E::kTorque);
  static constexpr bool kHeat = (false || ... || E::kHeat);
  static constexpr int kInertia = (0 + ... + static_cast<int>(E::kInertia));
  static_assert(kInertia <= 1, "at most one effect may change the parcels' inertia");
};

template <bool Store, class... E, std::size_t... K>
double forced_euler(const EulerArrays& a, std::size_t n, double dt, std::index_sequence<K...>,
                    const E&... effects) {
  using Roles = PackRoles<E...>;
  // Local restrict copies (through the struct the compiler would assume aliasing).
  double* __restrict px = a.x;
  double* __restrict py = a.y;
  double* __restrict pvx = a.vx;
  double* __restrict pvy = a.vy;
  double* __restrict pw = a.omega;
  double* __restrict pT = a.temperature;
  const double* __restrict im = a.inv_mass;
  const double* __restrict ii = a.inv_inertia;
  const double* __restrict cfx = a.contact_fx;
  const double* __restrict cfy = a.contact_fy;
  const double* __restrict ctq = a.contact_torque;
  const double* __restrict xb = a.x_build;
  const double* __restrict yb = a.y_build;
  const double* __restrict is2 = a.inv_skin2;
  double* __restrict jx = a.impulse_x;
  double* __restrict jy = a.impulse_y;
  double* __restrict work = a.work;
  double* __restrict heat = a.heat;
  const double gx = a.gravity_x, gy = a.gravity_y, inv_c = a.inv_heat_capacity;
  double max_d2 = 0.0;
  // The body is a function of its own: its locals (the parcel, the parts), passed by reference to
  // the functors, are then not privatised per SIMD lane by the simd loop below (arrays of
  // structs the vectoriser cannot load) but scalarised once inlined.
  const auto parcel = [=](std::size_t i) __attribute__((always_inline)) {
    SubstepParcel p{pvx[i], pvy[i], pw[i], pT[i], im[i]};
    Parts<typename E::Part...> part;
    (force(effects, i, p, get<K>(part)), ...);
    double fx = p.exchanged_x, fy = p.exchanged_y;
    if constexpr (Roles::kLocal) {
      fx += p.local_x;
      fy += p.local_y;
    }
    if constexpr (Roles::kInertia == 1) {
      (accelerate(effects, i, p, Vec2{cfx[i] + fx, cfy[i] + fy}, Vec2{gx, gy}), ...);
      p.vx_new = p.vx + dt * p.ax;
      p.vy_new = p.vy + dt * p.ay;
    } else {
      p.vx_new = p.vx + dt * ((cfx[i] + fx) * im[i] + gx);
      p.vy_new = p.vy + dt * ((cfy[i] + fy) * im[i] + gy);
    }
    pvx[i] = p.vx_new;
    pvy[i] = p.vy_new;
    (after(effects, i, p, get<K>(part)), ...);
    if constexpr (Roles::kExchanges) {
      const double ex = p.exchanged_x, ey = p.exchanged_y;
      jx[i] += ex * dt;
      jy[i] += ey * dt;
      work[i] += (ex * 0.5 * (p.vx + p.vx_new) + ey * 0.5 * (p.vy + p.vy_new)) * dt;
    }
    double tq = ctq[i];
    if constexpr (Roles::kTorque) tq += p.torque;
    pw[i] = p.omega + dt * tq * ii[i];
    if constexpr (Roles::kHeat) {
      const double q = p.heat;
      pT[i] += dt * q * im[i] * inv_c;  // eq. (7)
      heat[i] += q * dt;
    }
    const double xn = px[i] + dt * p.vx_new, yn = py[i] + dt * p.vy_new;
    px[i] = xn;
    py[i] = yn;
    if constexpr (Store) (store(effects, i, get<K>(part)), ...);
    const double ddx = xn - xb[i], ddy = yn - yb[i];
    return (ddx * ddx + ddy * ddy) * is2[i];
  };
#pragma omp parallel if (n >= kParallelMinimum)
  {
    // Each thread's own copy: its pointers are then locals the vectoriser sees as invariant
    // (through the shared closure they would be reloaded, and gathered, every iteration).
    const auto own = parcel;
#pragma omp for simd schedule(static) reduction(max : max_d2)
    for (std::size_t i = 0; i < n; ++i) max_d2 = std::max(max_d2, own(i));
  }
  return max_d2;
}
}  // namespace forced_euler_detail

/// One sub-step of parcels [0, n); returns the largest squared displacement since the last
/// neighbour build in units of the parcel's skin. Store: the effects write their force parts.
template <bool Store, class... E>
double forced_euler(const EulerArrays& a, std::size_t n, double dt, const E&... effects) {
  return forced_euler_detail::forced_euler<Store>(a, n, dt, std::index_sequence_for<E...>{},
                                                  effects...);
}

}  // namespace dustlift
