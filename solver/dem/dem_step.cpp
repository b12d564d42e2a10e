// One DEM step: gather contact forces (Table 1), then symplectic Euler (paper Sect. 2.3).
#include <algorithm>
#include <cmath>

#include "solver/dem/contact_law.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {

double ParcelSystem::wall_position(int w) const {
  const DemDomain& d = cfg_.domain;
  return w == 0 ? d.y_min : w == 1 ? d.y_max : w == 2 ? d.x_min : d.x_max;
}

void ParcelSystem::step(double dt) {
  if (needs_rebuild_) rebuild_neighbours();
  compute_contacts(dt);
  integrate(dt);
  time_ += dt;
  ++steps_;
}

void ParcelSystem::compute_contacts(double dt) {
  const std::size_t n = size();
  const ContactParams pc = cfg_.contact;
  const ContactParams wc = cfg_.wall_contact;
  const double lx = length_x_;
  // Active walls: outward normal from the parcel towards the wall, and the wall plane.
  struct ActiveWall { int slot; double nx, ny, pos; };
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
  const std::int32_t* __restrict off = nbr_offset.data();
  const std::int32_t* __restrict nj = nbr_index.data();
  const std::int8_t* __restrict nim = nbr_image.data();
  double* __restrict ndelta = nbr_delta.data();
  double* __restrict wdelta = wall_delta.data();
  double* __restrict fx_out = contact_fx.data();
  double* __restrict fy_out = contact_fy.data();
  double* __restrict tq_out = contact_torque.data();
  const std::uint8_t* __restrict wmask = wall_mask_.data();

#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = px[i], yi = py[i], vxi = pvx[i], vyi = pvy[i], ri = pr[i];
    const double rwi = ri * pw[i];
    double fx = 0.0, fy = 0.0, tq = 0.0;
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
      const ContactResult c = contact_force(pc, nx, ny, rs - dist, ux, uy, ndelta[k], ri, dt);
      ndelta[k] = c.delta_t;
      fx += c.fx;
      fy += c.fy;
      tq += c.torque;
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
        continue;
      }
      // The wall is at rest: u = -u_i - r_i w_i z x n.
      const double ux = -vxi + rwi * wall.ny;
      const double uy = -vyi - rwi * wall.nx;
      const ContactResult c = contact_force(wc, wall.nx, wall.ny, ri - gap, ux, uy, delta, ri, dt);
      delta = c.delta_t;
      fx += c.fx;
      fy += c.fy;
      tq += c.torque;
    }
    fx_out[i] = fx;
    fy_out[i] = fy;
    tq_out[i] = tq;
  }
}

namespace {

/// Arrays one integration pass reads and writes.
struct IntegrateArrays {
  double* __restrict x;
  double* __restrict y;
  double* __restrict vx;
  double* __restrict vy;
  double* __restrict omega;
  double* __restrict temperature;
  const double* __restrict inv_m;
  const double* __restrict inv_I;
  const double* __restrict fx;
  const double* __restrict fy;
  const double* __restrict torque;
  const double* __restrict ext_fx;  ///< sum of drag, Magnus, pressure (External only)
  const double* __restrict ext_fy;
  const double* __restrict ext_torque;
  const double* __restrict heat;
  const double* __restrict x_build;
  const double* __restrict y_build;
};

/// Symplectic Euler for all parcels; returns the largest squared displacement since the
/// last neighbour build. The plain variant (DEM alone) has no branch and vectorises.
template <bool External, bool Thermal>
double integrate_kernel(const IntegrateArrays& a, std::size_t n, double dt, double gx, double gy,
                        double inv_c) {
  // Local restrict copies: through the struct the compiler would assume the stores may
  // change the pointers themselves, and would not vectorise.
  double* __restrict px = a.x;
  double* __restrict py = a.y;
  double* __restrict pvx = a.vx;
  double* __restrict pvy = a.vy;
  double* __restrict pw = a.omega;
  double* __restrict pT = a.temperature;
  const double* __restrict im = a.inv_m;
  const double* __restrict ii = a.inv_I;
  const double* __restrict cfx = a.fx;
  const double* __restrict cfy = a.fy;
  const double* __restrict ctq = a.torque;
  const double* __restrict efx = a.ext_fx;
  const double* __restrict efy = a.ext_fy;
  const double* __restrict etq = a.ext_torque;
  const double* __restrict heat = a.heat;
  const double* __restrict xb = a.x_build;
  const double* __restrict yb = a.y_build;
  double max_d2 = 0.0;
#pragma omp parallel for simd schedule(static) reduction(max : max_d2) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    double fx = cfx[i], fy = cfy[i], m = ctq[i];
    if constexpr (External) {
      fx += efx[i];
      fy += efy[i];
      m += etq[i];
    }
    const double vxn = pvx[i] + dt * (fx * im[i] + gx);
    const double vyn = pvy[i] + dt * (fy * im[i] + gy);
    pvx[i] = vxn;
    pvy[i] = vyn;
    const double xn = px[i] + dt * vxn, yn = py[i] + dt * vyn;
    px[i] = xn;
    py[i] = yn;
    pw[i] += dt * m * ii[i];
    if constexpr (Thermal) pT[i] += dt * heat[i] * im[i] * inv_c;  // eq. (7)
    const double ddx = xn - xb[i], ddy = yn - yb[i];
    max_d2 = std::max(max_d2, ddx * ddx + ddy * ddy);
  }
  return max_d2;
}

}  // namespace

void ParcelSystem::integrate(double dt) {
  const std::size_t n = size();
  if (external_forces) {
    // The coupling's parts enter as one sum per component (fixed order: drag, Magnus, pressure).
    ext_fx_.resize(n);
    ext_fy_.resize(n);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
    for (std::size_t i = 0; i < n; ++i) {
      ext_fx_[i] = drag_fx[i] + magnus_fx[i] + pressure_fx[i];
      ext_fy_[i] = drag_fy[i] + magnus_fy[i] + pressure_fy[i];
    }
  }
  const IntegrateArrays a{x.data(), y.data(), vx.data(), vy.data(), omega.data(), temperature.data(),
                          inv_mass_real_.data(), inv_inertia_real_.data(), contact_fx.data(),
                          contact_fy.data(), contact_torque.data(), ext_fx_.data(), ext_fy_.data(),
                          fluid_torque.data(), heat_rate.data(), x_build_.data(), y_build_.data()};
  const double gx = cfg_.gravity_x, gy = cfg_.gravity_y, inv_c = 1.0 / cfg_.heat_capacity;
  double max_d2 = 0.0;
  if (external_forces) {
    max_d2 = integrate_temperature ? integrate_kernel<true, true>(a, n, dt, gx, gy, inv_c)
                                   : integrate_kernel<true, false>(a, n, dt, gx, gy, inv_c);
  } else {
    max_d2 = integrate_temperature ? integrate_kernel<false, true>(a, n, dt, gx, gy, inv_c)
                                   : integrate_kernel<false, false>(a, n, dt, gx, gy, inv_c);
  }
  // Two parcels each moving skin/2 towards each other can just reach: rebuild then.
  if (4.0 * max_d2 > skin_ * skin_) needs_rebuild_ = true;
}

}  // namespace dustlift
