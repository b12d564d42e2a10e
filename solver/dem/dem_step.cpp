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
        ndelta[k] = 0.0;  // not touching: the tangential spring is released
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
    for (int w = 0; w < n_walls; ++w) {
      const ActiveWall& wall = walls[w];
      double& delta = wdelta[i * kWallCount + wall.slot];
      // Only one of (nx, ny) is non-zero; the distance along it is what matters.
      const double gap = wall.nx != 0.0 ? wall.nx * (wall.pos - xi) : wall.ny * (wall.pos - yi);
      if (gap >= ri) {
        delta = 0.0;
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

void ParcelSystem::integrate(double dt) {
  const std::size_t n = size();
  const double gx = cfg_.gravity_x, gy = cfg_.gravity_y;
  const bool external = external_forces;
  const bool thermal = integrate_temperature;
  const double inv_c = 1.0 / cfg_.heat_capacity;
  double* __restrict px = x.data();
  double* __restrict py = y.data();
  double* __restrict pvx = vx.data();
  double* __restrict pvy = vy.data();
  double* __restrict pw = omega.data();
  const double* __restrict im = inv_mass_real_.data();
  const double* __restrict ii = inv_inertia_real_.data();
  const double* __restrict fx = contact_fx.data();
  const double* __restrict fy = contact_fy.data();
  const double* __restrict tq = contact_torque.data();
  const double* __restrict xb = x_build_.data();
  const double* __restrict yb = y_build_.data();
  double max_d2 = 0.0;
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum) reduction(max : max_d2)
  for (std::size_t i = 0; i < n; ++i) {
    double ax = fx[i], ay = fy[i], m = tq[i];
    if (external) {
      ax += drag_fx[i] + magnus_fx[i] + pressure_fx[i];
      ay += drag_fy[i] + magnus_fy[i] + pressure_fy[i];
      m += fluid_torque[i];
    }
    const double vxn = pvx[i] + dt * (ax * im[i] + gx);
    const double vyn = pvy[i] + dt * (ay * im[i] + gy);
    pvx[i] = vxn;
    pvy[i] = vyn;
    const double xn = px[i] + dt * vxn, yn = py[i] + dt * vyn;
    px[i] = xn;
    py[i] = yn;
    pw[i] += dt * m * ii[i];
    if (thermal) temperature[i] += dt * heat_rate[i] * im[i] * inv_c;  // eq. (7)
    const double ddx = xn - xb[i], ddy = yn - yb[i];
    max_d2 = std::max(max_d2, ddx * ddx + ddy * ddy);
  }
  // Two parcels each moving skin/2 towards each other can just reach: rebuild then.
  if (4.0 * max_d2 > skin_ * skin_) needs_rebuild_ = true;
}

}  // namespace dustlift
