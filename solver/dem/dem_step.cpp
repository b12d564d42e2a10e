// One DEM step: gather contact forces (Table 1), then symplectic Euler (paper Sect. 2.3).
#include <algorithm>
#include <cmath>
#include <tuple>

#include "solver/dem/contact_effects/contact_list.hpp"
#include "solver/dem/contact_kernel.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/contact.hpp"

namespace dustlift {

void ParcelSystem::update_stepped_count() {
  if (!stepped_.valid()) {
    stepped_count_ = size();
    return;
  }
  const std::vector<double>& a = column(stepped_);
  std::size_t k = a.size();
  while (k > 0 && a[k - 1] == 0.0) --k;
  stepped_count_ = k;
}

double ParcelSystem::wall_position(int w) const {
  const DemDomain& d = cfg_.domain;
  return w == 0 ? d.y_min : w == 1 ? d.y_max : w == 2 ? d.x_min : d.x_max;
}

void ParcelSystem::step(double dt) {
  step_with_parts(dt, true);
}

void ParcelSystem::step_with_parts(double dt, bool store_parts) {
  if (needs_rebuild_) {
    const ScopedTimer t(timings_.rebuild);
    rebuild_neighbours();
    update_stepped_count();  // the sort moved the stepped parcels
  }
  {
    const ScopedTimer t(timings_.contacts);
    compute_contacts(dt);
  }
  const ScopedTimer t(timings_.integrate);
  integrate(dt, store_parts);
  if (ranks_ != nullptr) {
    // Copies take their owners' new states; a rebuild anywhere is a rebuild everywhere.
    std::vector<double>* const kinematics[] = {&x, &y, &vx, &vy, &omega};
    ranks_->refresh_copies(*this, kinematics);
    needs_rebuild_ = ranks_->any(needs_rebuild_);
  }
  parcel_substeps_ += static_cast<long long>(stepped_count());
  time_ += dt;
  ++steps_;
}

void ParcelSystem::compute_contacts(double dt) {
  const bool restitution = cfg_.contact.restitution > 0.0 || cfg_.wall_contact.restitution > 0.0;
  if (!counts_known_) {
    // Whether any two parcels hold different real counts (size classes, or layer-file parcels
    // of different diameters): only then the pair rule below is needed, and a layer of one
    // count runs the plain per-real-particle pass. The same pass on every rank (the parcel
    // list changes at rebuilds, which all ranks make together).
    bool mixed = false;
    for (std::size_t i = 1; i < n_real.size() && !mixed; ++i) mixed = n_real[i] != n_real[0];
    mixed_counts_ = ranks_ != nullptr ? ranks_->any(mixed) : mixed;
    counts_known_ = true;
  }
  // A restitution is the material's: every pair's dashpot follows its own reduced mass.
  const bool pair_damping = restitution;
  // The pass of this combination of options and active contact units (contact_effects/).
  with_active_contact_units(cfg_, [&](const auto&... units) {
    if (mixed_counts_) {
      if (pair_damping)
        contacts_pass<true, true>(dt, units...);
      else
        contacts_pass<true, false>(dt, units...);
    } else {
      if (pair_damping)
        contacts_pass<false, true>(dt, units...);
      else
        contacts_pass<false, false>(dt, units...);
    }
  });
}

/// A chunk of parcels is computed parcel by parcel once 1 / kTouchingShareForParcelWise of its
/// listed pairs touched in the last pass (measured: slot by slot was 1.4x faster on a loose
/// layer with 1 % of its pairs touching, and the paper scene's contacts 1.5x slower with every
/// chunk slot by slot, its resting bed's chunks having 30-80 % touching).
constexpr std::int32_t kTouchingShareForParcelWise = 16;

template <bool Mixed, bool PairDamping, class... Units>
void ParcelSystem::contacts_pass(double dt, const Units&... units) {
  const std::size_t n = stepped_count();
  contact_pass::ContactKernel<Mixed, PairDamping, Units...> k(units...);
  k.pc = cfg_.contact;
  k.wc = cfg_.wall_contact;
  k.lx = length_x_;
  k.dt = dt;
  // A given restitution: the dashpot of each pair (and of each parcel at a wall) follows its
  // reduced mass, h = c(e) sqrt(m_eff k_n) (docs/dem.md, "Restitution").
  k.pair_follows = PairDamping && k.pc.restitution > 0.0;
  k.wall_follows = PairDamping && k.wc.restitution > 0.0;
  k.pair_factor = pair_damping_factor_;
  k.wall_factor = wall_damping_factor_;
  k.columns = ContactColumns{real_diameter.data()};
  k.n_walls = 0;
  const DemDomain& d = cfg_.domain;
  if (d.wall_bottom) k.walls[k.n_walls++] = {0, 0.0, -1.0, wall_position(0)};
  if (d.wall_top) k.walls[k.n_walls++] = {1, 0.0, 1.0, wall_position(1)};
  if (d.wall_left) k.walls[k.n_walls++] = {2, -1.0, 0.0, wall_position(2)};
  if (d.wall_right) k.walls[k.n_walls++] = {3, 1.0, 0.0, wall_position(3)};
  k.px = x.data();
  k.py = y.data();
  k.pvx = vx.data();
  k.pvy = vy.data();
  k.pw = omega.data();
  k.pr = radius.data();
  k.pn = n_real.data();
  k.pim = inv_mass_real.data();
  k.ids = id.data();
  k.off = nbr_offset.data();
  k.nj = nbr_index.data();
  k.nim = nbr_image.data();
  k.ndelta = nbr_delta.data();
  k.wdelta = wall_delta.data();
  k.fx_out = contact_fx.data();
  k.fy_out = contact_fy.data();
  k.tq_out = contact_torque.data();
  k.wmask = wall_mask.data();
  k.copy = rank_copy.empty() ? nullptr : rank_copy.data();
  // Each parcel gathers its own forces: any schedule gives the same bits. Each thread its own
  // copy of the kernel: its members are then locals the compiler keeps in registers (through
  // the shared one they would be reloaded after every store). Without units, chunks go to
  // the threads in contiguous blocks as the integration's parcels do, so a thread integrates
  // the forces it wrote, in its own core's cache: on the reference layer 1.07x on 2 threads
  // against dynamic chunks, and the quickstart as fast, although its contacts cluster at the
  // disturbed end of the x-ordered parcels.
  if constexpr (sizeof...(Units) == 0) {
    constexpr std::size_t chunk = kContactChunk;
    const std::size_t chunks = (n + chunk - 1) / chunk;
    // Sized once for all parcels (the stepped ones are a prefix of them): no allocation per step.
    if (chunk_touching_.size() < (size() + chunk - 1) / chunk)
      chunk_touching_.resize((size() + chunk - 1) / chunk, 0);
#pragma omp parallel for schedule(static) firstprivate(k) if (n >= kParallelMinimum)
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::size_t i0 = c * chunk, i1 = std::min(n, (c + 1) * chunk);
      // Where few listed pairs touched in the last pass (a loose layer, a cloud) slot by slot
      // is faster; in a resting bed most pairs touch and parcel by parcel is. Both give the
      // same bits. `touching` counts the pairs that touched (slot by slot) or the parcels
      // with a contact force (parcel by parcel), either a bound on the touching share.
      const std::int32_t slots = nbr_offset[i1] - nbr_offset[i0];
      std::int32_t& touching = chunk_touching_[c];
      const bool by_slot = traversal_ == ContactTraversal::Adaptive
                               ? touching < slots / kTouchingShareForParcelWise
                               : traversal_ == ContactTraversal::BySlot;
      if (by_slot) {
        touching = k.parcels_by_slots(i0, i1);
      } else {
        // A copy whose address never escapes: its members then stay in registers.
        const auto kernel = k;
        for (std::size_t i = i0; i < i1; ++i) kernel.parcel(i);
        touching = 0;
        for (std::size_t i = i0; i < i1; ++i) touching += kernel.forced(i) ? 1 : 0;
      }
    }
  } else {
#pragma omp parallel for schedule(dynamic, 1024) firstprivate(k) if (n >= kParallelMinimum)
    for (std::size_t i = 0; i < n; ++i) k.parcel(i);
  }
}

namespace {

/// Symplectic Euler of the parcels under contacts (and gravity) alone; returns the largest
/// squared displacement since the last neighbour build in units of the parcel's own skin
/// (is2 = 1 / skin^2): above 1 the list must be rebuilt. Branch-free: it vectorises.
double integrate_plain(double* __restrict px, double* __restrict py, double* __restrict pvx,
                       double* __restrict pvy, double* __restrict pw, const double* __restrict im,
                       const double* __restrict ii, const double* __restrict cfx,
                       const double* __restrict cfy, const double* __restrict ctq,
                       const double* __restrict xb, const double* __restrict yb,
                       const double* __restrict is2, std::size_t n, double dt, double gx,
                       double gy) {
  double max_d2 = 0.0;
#pragma omp parallel for simd schedule(static) reduction(max : max_d2) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    const double vxn = pvx[i] + dt * (cfx[i] * im[i] + gx);
    const double vyn = pvy[i] + dt * (cfy[i] * im[i] + gy);
    pvx[i] = vxn;
    pvy[i] = vyn;
    const double xn = px[i] + dt * vxn, yn = py[i] + dt * vyn;
    px[i] = xn;
    py[i] = yn;
    pw[i] += dt * ctq[i] * ii[i];
    const double ddx = xn - xb[i], ddy = yn - yb[i];
    max_d2 = std::max(max_d2, (ddx * ddx + ddy * ddy) * is2[i]);
  }
  return max_d2;
}

}  // namespace

void ParcelSystem::integrate(double dt, bool store_parts) {
  double max_d2 = 0.0;
  if (forcing_) {
    max_d2 = forcing_->substep(*this, stepped_count(), dt, store_parts);
  } else {
    max_d2 =
        integrate_plain(x.data(), y.data(), vx.data(), vy.data(), omega.data(),
                        inv_mass_real.data(), inv_inertia_real.data(), contact_fx.data(),
                        contact_fy.data(), contact_torque.data(), x_build.data(), y_build.data(),
                        inv_skin2.data(), stepped_count(), dt, cfg_.gravity_x, cfg_.gravity_y);
  }
  // A parcel moved more than its skin: a pair may now be closer than the list knows.
  if (max_d2 > 1.0) needs_rebuild_ = true;
}

}  // namespace dustlift
