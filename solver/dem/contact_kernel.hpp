#pragma once
// The contact pass's kernel (ParcelSystem::contacts_pass, dem_step.cpp): the laws and columns
// it reads, what it does for one parcel, and its walk over a chunk's neighbour slots. Only
// dem_step.cpp includes it; everything is inlined into the pass's loops.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "solver/dem/contact_effects/contact_list.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/contact.hpp"

namespace dustlift::contact_pass {

/// A wall the parcels meet: its slot, the outward normal from the parcel towards the wall,
/// and the wall plane.
struct ActiveWall {
  int slot;
  double nx, ny, pos;
};

/// One parcel of the contact pass: its state, and its force sums per real particle.
struct ContactParcel {
  std::size_t i;
  double x, y, vx, vy, r, rw;  ///< rw = r omega
  double fx = 0.0, fy = 0.0, tq = 0.0;
};

/// Where slot k's partner j sits from a parcel at (xi, yi) of radius ri: (dx, dy), its square
/// d2, and the radii's sum rs. One expression for the slot-wise and parcel-wise passes, so
/// both decide "touching" (d2 < rs^2) alike, to the bit.
struct Separation {
  double dx, dy, d2, rs;
};
[[gnu::always_inline]] inline Separation slot_separation(const double* px, const double* py,
                                                         const double* pr, const std::int8_t* image,
                                                         double lx, double xi, double yi, double ri,
                                                         std::int32_t j, std::int32_t k) {
  const double dx = (px[j] + image[k] * lx) - xi, dy = py[j] - yi;
  return {dx, dy, dx * dx + dy * dy, ri + pr[j]};
}

/// The contact pass's laws and columns (ParcelSystem::contacts_pass), and what it does for
/// one parcel. Its members, the active contact units' forces included, are inlined into the
/// pass's loop: no call per parcel or pair.
template <bool Mixed, bool PairDamping, class... Units>
struct ContactKernel {
  explicit ContactKernel(const Units&... u) : units(u...) {}

  ContactParams pc, wc;
  double lx, dt;
  bool pair_follows, wall_follows;
  double pair_factor, wall_factor;
  std::tuple<Units...> units;  ///< the active contact units, in their order (contact_list.hpp)
  ContactColumns columns;      ///< what they read
  ActiveWall walls[kWallCount];
  int n_walls;
  const double *px, *py, *pvx, *pvy, *pw, *pr, *pn, *pim;
  const std::int32_t *ids, *off, *nj;
  const std::int8_t* nim;
  double *ndelta, *wdelta, *fx_out, *fy_out, *tq_out;
  const std::uint8_t* wmask;
  const std::uint8_t* copy;  ///< null on one rank

  [[gnu::always_inline]] inline void parcel(std::size_t i) const {
    // A rank copy's forces are its owner's (its state is refreshed after every sub-step).
    if (copy != nullptr && copy[i] != 0) {
      fx_out[i] = fy_out[i] = tq_out[i] = 0.0;
      return;
    }
    ContactParcel p = state_of(i);
    for (std::int32_t k = off[i]; k < off[i + 1]; ++k) pair(p, k);
    add_walls(p, wmask[i]);
    store(p);
  }

  /// Parcel i's state, its force sums zero.
  [[gnu::always_inline]] inline ContactParcel state_of(std::size_t i) const {
    return {i, px[i], py[i], pvx[i], pvy[i], pr[i], pr[i] * pw[i]};
  }
  /// Parcel i's state with the force sums stored so far in this pass.
  [[gnu::always_inline]] inline ContactParcel stored_state_of(std::size_t i) const {
    ContactParcel p = state_of(i);
    p.fx = fx_out[i];
    p.fy = fy_out[i];
    p.tq = tq_out[i];
    return p;
  }
  [[gnu::always_inline]] inline void store(const ContactParcel& p) const {
    fx_out[p.i] = p.fx;
    fy_out[p.i] = p.fy;
    tq_out[p.i] = p.tq;
  }
  /// The walls in the parcel's reach (`mask`, from the last rebuild).
  [[gnu::always_inline]] inline void add_walls(ContactParcel& p, unsigned mask) const {
    for (int w = 0; w < n_walls && mask != 0; ++w) {
      if ((mask & (1u << walls[w].slot)) != 0) wall(p, walls[w]);
    }
  }

  /// Whether parcel i has a contact force (touches a partner or a wall).
  [[gnu::always_inline]] inline bool forced(std::size_t i) const {
    return fx_out[i] != 0.0 || fy_out[i] != 0.0;
  }

  /// Adds one pair's per-real-particle force on i (the pair rule between counts).
  [[gnu::always_inline]] inline void add_pair(ContactParcel& p, std::int32_t j, double pfx,
                                              double pfy, double ptq) const {
    const std::size_t i = p.i;
    if (!Mixed || pn[j] == pn[i]) {
      p.fx += pfx;
      p.fy += pfy;
      p.tq += ptq;
    } else {
      // Parcels of different real counts (size classes, or file parcels of different
      // diameters): the pair stands for min(n_i, n_j) real contacts, so each side's
      // per-real-particle force is scaled by min(n_i, n_j) / n_i and the parcels' totals
      // n_i F_i = -n_j F_j are equal and opposite (docs/dem.md, "Polydisperse layers").
      const double share = std::min(pn[i], pn[j]) / pn[i];
      p.fx += pfx * share;
      p.fy += pfy * share;
      p.tq += ptq * share;
    }
  }

  [[gnu::always_inline]] inline Separation separation(double xi, double yi, double ri,
                                                      std::int32_t j, std::int32_t k) const {
    return slot_separation(px, py, pr, nim, lx, xi, yi, ri, j, k);
  }

  /// The pair in neighbour slot k.
  [[gnu::always_inline]] inline void pair(ContactParcel& p, std::int32_t k) const {
    const std::int32_t j = nj[k];
    const Separation sep = separation(p.x, p.y, p.r, j, k);
    if (sep.d2 >= sep.rs * sep.rs) {
      // Not touching: the tangential spring is released (written only when it held
      // something: most slots are idle, and stores to them dominated the profile).
      if (ndelta[k] != 0.0) ndelta[k] = 0.0;
      // The units' attraction across the gap, along (dx, dy) towards j.
      (pair_gap(std::get<Units>(units), p, j, sep.dx, sep.dy, sep.d2, sep.rs), ...);
      return;
    }
    touching_pair(p, k, j, sep.dx, sep.dy, sep.d2, sep.rs);
  }

  /// Slot k's pair with j, known to touch (separation (dx, dy), d2 < rs^2).
  [[gnu::always_inline]] inline void touching_pair(ContactParcel& p, std::int32_t k, std::int32_t j,
                                                   double dx, double dy, double d2,
                                                   double rs) const {
    const std::size_t i = p.i;
    const double rj = pr[j];
    const double dist = std::sqrt(d2);
    // Coincident centres have no normal; pick one from the ids so both sides agree.
    double nx, ny;
    if (dist > 0.0) {
      nx = dx / dist;
      ny = dy / dist;
    } else {
      nx = 0.0;
      ny = ids[i] < ids[j] ? 1.0 : -1.0;
    }
    const double wsum = p.rw + rj * pw[j];
    // u_ij = u_j - u_i - (r_i w_i + r_j w_j) z x n, z x n = (-ny, nx)  (§3.6)
    const double ux = (pvx[j] - p.vx) + wsum * ny;
    const double uy = (pvy[j] - p.vy) - wsum * nx;
    ContactParams law = pc;
    if constexpr (PairDamping) {
      if (pair_follows)
        law.damping =
            pair_damping(pair_factor, pair_effective_mass(pim[i], pim[j], pn[i], pn[j]), pc.k_n);
    }
    ContactResult c = contact_force(law, nx, ny, rs - dist, ux, uy, ndelta[k], p.r, dt);
    ndelta[k] = c.delta_t;
    // The units' attraction along n, towards j, added to the spring-dashpot force.
    (pair_touching(std::get<Units>(units), c, i, j, nx, ny), ...);
    add_pair(p, j, c.fx, c.fy, c.torque);
  }

  /// Parcels [i0, i1) slot by slot, for a pass without contact units (nothing acts across a
  /// gap): in blocks of listed slots, one branch-free loop finds each slot's parcel and
  /// whether its pair touches, then only the touching pairs are computed, then the walls.
  /// Per parcel the sums are those of parcel(): its pairs in slot order, then its walls.
  /// Most slots of a layer are idle, and a loop per parcel over a few slots each spent its
  /// time on the loop's exits, not on the pairs.
  /// Returns how many pairs touch.
  [[gnu::noinline]] std::int32_t parcels_by_slots(std::size_t i0, std::size_t i1) const {
    static_assert(sizeof...(Units) == 0, "units acting across a gap need every slot visited");
    for (std::size_t i = i0; i < i1; ++i) fx_out[i] = fy_out[i] = tq_out[i] = 0.0;
    const std::int32_t k_end = off[i1];
    std::int32_t touching_pairs = 0;
    std::size_t owner = i0;  // the parcel of the block's first slot
    for (std::int32_t s0 = off[i0]; s0 < k_end; s0 += kSlotBlock) {
      const std::int32_t s1 = std::min(s0 + kSlotBlock, k_end);
      while (off[owner + 1] <= s0) ++owner;
      std::size_t last = owner;  // the parcel of the block's last slot
      while (off[last + 1] < s1) ++last;
      // Slot s belongs to the last parcel whose list starts at or before s: count the
      // parcels starting at each slot of the block, then sum along the block.
      std::int32_t starts[kSlotBlock];
      for (std::int32_t s = 0; s < s1 - s0; ++s) starts[s] = 0;
      for (std::size_t i = owner + 1; i <= last; ++i) ++starts[off[i] - s0];
      std::int32_t owners[kSlotBlock];
      auto running = static_cast<std::int32_t>(owner);
      for (std::int32_t s = 0; s < s1 - s0; ++s) owners[s] = running += starts[s];
      std::int32_t touching[kSlotBlock];
      const std::int32_t n_touching = find_touching(s0, s1, owners, touching);
      touching_pairs += n_touching;
      // Each parcel's touching pairs in slot order, summed onto what its earlier blocks'
      // pairs gave (the same operations as parcel()'s, fused multiply-adds included).
      for (std::int32_t t = 0; t < n_touching;) {
        const auto i = static_cast<std::size_t>(owners[touching[t] - s0]);
        ContactParcel p = stored_state_of(i);
        for (; t < n_touching && static_cast<std::size_t>(owners[touching[t] - s0]) == i; ++t) {
          const std::int32_t k = touching[t], j = nj[k];
          const Separation sep = separation(p.x, p.y, p.r, j, k);
          touching_pair(p, k, j, sep.dx, sep.dy, sep.d2, sep.rs);
        }
        store(p);
      }
    }
    for (std::size_t i = i0; i < i1; ++i) {
      const unsigned mask = wmask[i];
      if (mask == 0 || (copy != nullptr && copy[i] != 0)) continue;
      ContactParcel p = stored_state_of(i);
      add_walls(p, mask);
      store(p);
    }
    return touching_pairs;
  }
  static constexpr std::int32_t kSlotBlock = 512;

  /// Slots [s0, s1) whose pairs touch, listed in `touching` (returns how many); releases the
  /// tangential spring of the others. Locals, not members, in the loop: through `this` they
  /// would be reloaded after every store.
  [[gnu::always_inline]] inline std::int32_t find_touching(std::int32_t s0, std::int32_t s1,
                                                           const std::int32_t* owners,
                                                           std::int32_t* touching) const {
    const double *const x = px, *const y = py, *const r = pr;
    const std::int32_t* const partner = nj;
    const std::int8_t* const image = nim;
    const std::uint8_t* const copied = copy;
    double* const delta = ndelta;
    const double length = lx;
    std::int32_t n_touching = 0;
    for (std::int32_t s = 0; s < s1 - s0; ++s) {
      const std::int32_t k = s0 + s, i = owners[s];
      const Separation sep =
          slot_separation(x, y, r, image, length, x[i], y[i], r[i], partner[k], k);
      const bool touches = sep.d2 < sep.rs * sep.rs;
      // A rank copy's forces and springs are its owner's.
      const bool skip = copied != nullptr && copied[i] != 0;
      // Not touching: the tangential spring is released.
      if (!touches && !skip && delta[k] != 0.0) delta[k] = 0.0;
      touching[n_touching] = k;
      n_touching += touches && !skip ? 1 : 0;
    }
    return n_touching;
  }

  /// The parcel against a wall within its reach.
  [[gnu::always_inline]] inline void wall(ContactParcel& p, const ActiveWall& w) const {
    const std::size_t i = p.i;
    double& delta = wdelta[i * kWallCount + w.slot];
    // Only one of (nx, ny) is non-zero; the distance along it is what matters.
    const double gap = w.nx != 0.0 ? w.nx * (w.pos - p.x) : w.ny * (w.pos - p.y);
    if (gap >= p.r) {
      if (delta != 0.0) delta = 0.0;
      (wall_gap(std::get<Units>(units), p, w, gap - p.r), ...);
      return;
    }
    // The wall is at rest: u = -u_i - r_i w_i z x n.
    const double ux = -p.vx + p.rw * w.ny;
    const double uy = -p.vy - p.rw * w.nx;
    ContactParams law = wc;
    if constexpr (PairDamping) {
      if (wall_follows) law.damping = pair_damping(wall_factor, 1.0 / pim[i], wc.k_n);
    }
    const ContactResult c = contact_force(law, w.nx, w.ny, p.r - gap, ux, uy, delta, p.r, dt);
    delta = c.delta_t;
    p.fx += c.fx;
    p.fy += c.fy;
    p.tq += c.torque;
    (wall_touching(std::get<Units>(units), p, w), ...);
  }

  // One unit's normal force (> 0: attraction), where the pair and wall terms above add it.
  template <class U>
  [[gnu::always_inline]] inline void pair_gap(const U& u, ContactParcel& p, std::int32_t j,
                                              double dx, double dy, double d2, double rs) const {
    double f, dist;
    if (u.pair_gap(columns, p.i, j, d2, rs, f, dist))
      add_pair(p, j, f * dx / dist, f * dy / dist, 0.0);
  }
  template <class U>
  [[gnu::always_inline]] inline void pair_touching(const U& u, ContactResult& c, std::size_t i,
                                                   std::int32_t j, double nx, double ny) const {
    double f;
    if (u.pair_touching(columns, i, j, f)) {
      c.fx += f * nx;
      c.fy += f * ny;
    }
  }
  template <class U>
  [[gnu::always_inline]] inline void wall_gap(const U& u, ContactParcel& p, const ActiveWall& w,
                                              double gap) const {
    double f;
    if (u.wall_gap(columns, p.i, gap, f)) {
      p.fx += f * w.nx;
      p.fy += f * w.ny;
    }
  }
  template <class U>
  [[gnu::always_inline]] inline void wall_touching(const U& u, ContactParcel& p,
                                                   const ActiveWall& w) const {
    double f;
    if (u.wall_touching(columns, p.i, f)) {
      p.fx += f * w.nx;
      p.fy += f * w.ny;
    }
  }
};

}  // namespace dustlift::contact_pass
