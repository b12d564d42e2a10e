// One DEM step: gather contact forces (Table 1), then symplectic Euler (paper Sect. 2.3).
#include <algorithm>
#include <cmath>

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
  const bool cohesive = cfg_.cohesion.enabled() || cfg_.wall_cohesion.enabled();
  using Pass = void (ParcelSystem::*)(double);
  static constexpr Pass kPasses[8] = {
      &ParcelSystem::contacts_pass<false, false, false>,
      &ParcelSystem::contacts_pass<false, false, true>,
      &ParcelSystem::contacts_pass<false, true, false>,
      &ParcelSystem::contacts_pass<false, true, true>,
      &ParcelSystem::contacts_pass<true, false, false>,
      &ParcelSystem::contacts_pass<true, false, true>,
      &ParcelSystem::contacts_pass<true, true, false>,
      &ParcelSystem::contacts_pass<true, true, true>,
  };
  const int which = (mixed_counts_ ? 4 : 0) + (pair_damping ? 2 : 0) + (cohesive ? 1 : 0);
  (this->*kPasses[which])(dt);
}

template <bool Mixed, bool PairDamping, bool Cohesive>
void ParcelSystem::contacts_pass(double dt) {
  const std::size_t n = stepped_count();
  const ContactParams pc = cfg_.contact;
  const ContactParams wc = cfg_.wall_contact;
  const double lx = length_x_;
  // A given restitution: the dashpot of each pair (and of each parcel at a wall) follows its
  // reduced mass, h = c(e) sqrt(m_eff k_n) (docs/dem.md, "Restitution").
  const bool pair_follows = PairDamping && pc.restitution > 0.0;
  const bool wall_follows = PairDamping && wc.restitution > 0.0;
  const double pair_factor = pair_damping_factor_, wall_factor = wall_damping_factor_;
  // Van der Waals cohesion per real pair (laws/cohesion.hpp): held at its pull-off force while
  // the parcels overlap, and down to the cut-off across a gap.
  const CohesionParams coh = cfg_.cohesion;
  const CohesionParams wcoh = cfg_.wall_cohesion;
  const bool pair_cohesion = Cohesive && coh.enabled();
  const bool wall_cohesion = Cohesive && wcoh.enabled();
  const double pair_reach = pair_reach_, wall_reach = wall_reach_;
  // Active walls: outward normal from the parcel towards the wall, and the wall plane.
  struct ActiveWall {
    int slot;
    double nx, ny, pos;
  };
  ActiveWall walls[kWallCount];
  int n_walls = 0;
  const DemDomain& d = cfg_.domain;
  if (d.wall_bottom) walls[n_walls++] = {0, 0.0, -1.0, wall_position(0)};
  if (d.wall_top) walls[n_walls++] = {1, 0.0, 1.0, wall_position(1)};
  if (d.wall_left) walls[n_walls++] = {2, -1.0, 0.0, wall_position(2)};
  if (d.wall_right) walls[n_walls++] = {3, 1.0, 0.0, wall_position(3)};

  const double* __restrict px = x.data();
  const double* __restrict py = y.data();
  const double* __restrict pvx = vx.data();
  const double* __restrict pvy = vy.data();
  const double* __restrict pw = omega.data();
  const double* __restrict pr = radius.data();
  const double* __restrict pn = n_real.data();
  const double* __restrict pim = inv_mass_real.data();
  const double* __restrict prd = real_diameter.data();
  const std::int32_t* __restrict off = nbr_offset.data();
  const std::int32_t* __restrict nj = nbr_index.data();
  const std::int8_t* __restrict nim = nbr_image.data();
  double* __restrict ndelta = nbr_delta.data();
  double* __restrict wdelta = wall_delta.data();
  double* __restrict fx_out = contact_fx.data();
  double* __restrict fy_out = contact_fy.data();
  double* __restrict tq_out = contact_torque.data();
  const std::uint8_t* __restrict wmask = wall_mask.data();
  // A rank copy's forces are its owner's (its state is refreshed after every sub-step).
  const std::uint8_t* __restrict copy = rank_copy.empty() ? nullptr : rank_copy.data();

  // Dynamic chunks: contacts cluster where the layer is disturbed, at one end of the x-ordered
  // parcels. Each parcel gathers its own forces: any schedule gives the same bits.
#pragma omp parallel for schedule(dynamic, 1024) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    if (copy != nullptr && copy[i] != 0) {
      fx_out[i] = fy_out[i] = tq_out[i] = 0.0;
      continue;
    }
    const double xi = px[i], yi = py[i], vxi = pvx[i], vyi = pvy[i], ri = pr[i];
    const double rwi = ri * pw[i];
    double fx = 0.0, fy = 0.0, tq = 0.0;
    // Adds one pair's per-real-particle force on i (the pair rule between counts).
    auto add_pair = [&](std::int32_t j, double pfx, double pfy, double ptq) {
      if (!Mixed || pn[j] == pn[i]) {
        fx += pfx;
        fy += pfy;
        tq += ptq;
      } else {
        // Parcels of different real counts (size classes, or file parcels of different
        // diameters): the pair stands for min(n_i, n_j) real contacts, so each side's
        // per-real-particle force is scaled by min(n_i, n_j) / n_i and the parcels' totals
        // n_i F_i = -n_j F_j are equal and opposite (docs/dem.md, "Polydisperse layers").
        const double share = std::min(pn[i], pn[j]) / pn[i];
        fx += pfx * share;
        fy += pfy * share;
        tq += ptq * share;
      }
    };
    for (std::int32_t k = off[i]; k < off[i + 1]; ++k) {
      const std::int32_t j = nj[k];
      const double rj = pr[j];
      const double dx = (px[j] + nim[k] * lx) - xi, dy = py[j] - yi;
      const double rs = ri + rj;
      const double d2 = dx * dx + dy * dy;
      if (d2 >= rs * rs) {
        // Not touching: the tangential spring is released (written only when it held
        // something: most slots are idle, and stores to them dominated the profile).
        if (ndelta[k] != 0.0) ndelta[k] = 0.0;
        if constexpr (Cohesive) {
          // The van der Waals tail across the gap, up to the cut-off.
          const double reach = rs + pair_reach;
          if (pair_cohesion && pair_reach > 0.0 && d2 < reach * reach) {
            const double dist = std::sqrt(d2);
            const double f = van_der_waals_force(
                coh, reduced_radius(0.5 * prd[i], 0.5 * prd[j]), dist - rs);
            add_pair(j, f * dx / dist, f * dy / dist, 0.0);
          }
        }
        continue;
      }
      const double dist = std::sqrt(d2);
      // Coincident centres have no normal; pick one from the ids so both sides agree.
      double nx, ny;
      if (dist > 0.0) {
        nx = dx / dist;
        ny = dy / dist;
      } else {
        nx = 0.0;
        ny = id[i] < id[j] ? 1.0 : -1.0;
      }
      const double wsum = rwi + rj * pw[j];
      // u_ij = u_j - u_i - (r_i w_i + r_j w_j) z x n, z x n = (-ny, nx)  (§3.6)
      const double ux = (pvx[j] - vxi) + wsum * ny;
      const double uy = (pvy[j] - vyi) - wsum * nx;
      ContactParams law = pc;
      if constexpr (PairDamping) {
        if (pair_follows)
          law.damping =
              pair_damping(pair_factor, pair_effective_mass(pim[i], pim[j], pn[i], pn[j]), pc.k_n);
      }
      ContactResult c = contact_force(law, nx, ny, rs - dist, ux, uy, ndelta[k], ri, dt);
      ndelta[k] = c.delta_t;
      if constexpr (Cohesive) {
        // Attraction along n, towards j; the Coulomb limit above saw the spring-dashpot load,
        // which holds the adhesion (DMT).
        if (pair_cohesion) {
          const double f = pull_off_force(coh, reduced_radius(0.5 * prd[i], 0.5 * prd[j]));
          c.fx += f * nx;
          c.fy += f * ny;
        }
      }
      add_pair(j, c.fx, c.fy, c.torque);
    }
    const unsigned mask = wmask[i];
    for (int w = 0; w < n_walls && mask != 0; ++w) {
      const ActiveWall& wall = walls[w];
      if ((mask & (1u << wall.slot)) == 0) continue;
      double& delta = wdelta[i * kWallCount + wall.slot];
      // Only one of (nx, ny) is non-zero; the distance along it is what matters.
      const double gap = wall.nx != 0.0 ? wall.nx * (wall.pos - xi) : wall.ny * (wall.pos - yi);
      if (gap >= ri) {
        if (delta != 0.0) delta = 0.0;
        if constexpr (Cohesive) {
          if (wall_cohesion && gap - ri < wall_reach) {
            const double f = van_der_waals_force(wcoh, 0.5 * prd[i], gap - ri);
            fx += f * wall.nx;
            fy += f * wall.ny;
          }
        }
        continue;
      }
      // The wall is at rest: u = -u_i - r_i w_i z x n.
      const double ux = -vxi + rwi * wall.ny;
      const double uy = -vyi - rwi * wall.nx;
      ContactParams law = wc;
      if constexpr (PairDamping) {
        if (wall_follows) law.damping = pair_damping(wall_factor, 1.0 / pim[i], wc.k_n);
      }
      const ContactResult c = contact_force(law, wall.nx, wall.ny, ri - gap, ux, uy, delta, ri, dt);
      delta = c.delta_t;
      fx += c.fx;
      fy += c.fy;
      tq += c.torque;
      if constexpr (Cohesive) {
        if (wall_cohesion) {
          // A sphere and a plane: R* = the real particle's radius.
          const double f = pull_off_force(wcoh, 0.5 * prd[i]);
          fx += f * wall.nx;
          fy += f * wall.ny;
        }
      }
    }
    fx_out[i] = fx;
    fy_out[i] = fy;
    tq_out[i] = tq;
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
