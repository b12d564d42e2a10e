#include "solver/coupling/gas_particle_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "solver/core/derivatives.hpp"
#include "solver/core/errors.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/gas/thermo.hpp"
#include "solver/gas/transport.hpp"

namespace dustlift {
namespace {

/// Below this many parcels a parallel region costs more than it saves.
constexpr std::size_t kParallelParcels = 4096;

/// cp(T) and c(T) of the configured thermodynamics.
struct ThermoAt {
  double cp, c, gamma;
};
ThermoAt thermo_at(const ThermoConfig& t, double T) {
  if (t.model == ThermoModel::CaloricallyPerfect) {
    const CaloricallyPerfectGas g(t.gamma, t.gas_constant);
    return {g.cp(T), std::sqrt(g.sound_speed_squared(T)), g.gamma(T)};
  }
  const ThermallyPerfectAir a(t.gas_constant);
  return {a.cp(T), std::sqrt(a.sound_speed_squared(T)), a.gamma(T)};
}


/// The particle models always need mu and lambda; an inviscid gas lends them the
/// Gordon-Wilke air values (the gas itself stays inviscid).
TransportProperties particle_transport(const TransportConfig& c, double T, double cp) {
  if (c.model == TransportModel::Inviscid) return air_transport_gordon_wilke(T);
  return transport_properties(c, T, cp);
}

void copy_edge_to_ghosts(const Grid2D& g, Field2D& f, int j0, int j1) {
  // Zero-gradient ghost values so that interpolation next to the boundary sees the edge cell.
  const int ng = g.ghosts();
  for (int j = std::max(j0, 0); j < std::min(j1, g.ny()); ++j) {
    for (int k = 1; k <= ng; ++k) {
      f(-k, j) = f(0, j);
      f(g.nx() - 1 + k, j) = f(g.nx() - 1, j);
    }
  }
  for (int i = -ng; i < g.nx() + ng; ++i) {
    for (int k = 1; k <= ng; ++k) {
      if (j0 <= 0) f(i, -k) = f(i, 0);
      if (j1 >= g.ny()) f(i, g.ny() - 1 + k) = f(i, g.ny() - 1);
    }
  }
}

}  // namespace

GasParticleCoupling::GasParticleCoupling(const Grid2D& grid, const CouplingConfig& config,
                                         const GasConfig& gas, const DemConfig& dem)
    : grid_(grid), cfg_(config), gas_cfg_(gas), dem_cfg_(dem),
      particle_volume_(std::numbers::pi / 6.0 * std::pow(dem.particle_diameter, 3)),
      alpha_p_(grid), src_x_(grid), src_y_(grid), src_e_(grid), cell_drag_(grid), cell_heat_(grid),
      cell_mass_(grid), cell_heat_capacity_(grid) {
  if (needs_vorticity()) vorticity_ = Field2D(grid);
  if (cfg_.pressure_force) {
    dpdx_ = Field2D(grid);
    dpdy_ = Field2D(grid);
  }
}

void GasParticleCoupling::restore_carried_state(const CarriedState& s) {
  if (s.alpha_p.size() != alpha_p_.size() || s.rows_touched < 0 || s.rows_touched > grid_.ny()) {
    throw std::invalid_argument("GasParticleCoupling: carried state does not fit the grid");
  }
  alpha_p_.raw() = s.alpha_p;
  rows_touched_ = s.rows_touched;
}

bool GasParticleCoupling::needs_vorticity() const { return cfg_.magnus || cfg_.rotation_torque; }

void GasParticleCoupling::row_range(const ParcelSystem& parcels, int& j0, int& j1) const {
  double ymin = grid_.y().end(), ymax = grid_.y().start();
  for (std::size_t i = 0; i < parcels.size(); ++i) {
    ymin = std::min(ymin, parcels.y[i]);
    ymax = std::max(ymax, parcels.y[i]);
  }
  // Two rows of margin: the interpolation quad and the 3-point derivative stencils.
  j0 = std::max(0, grid_.y().locate(ymin) - 2);
  j1 = std::min(grid_.ny(), grid_.y().locate(ymax) + 3);
}

void GasParticleCoupling::deposit_alpha(const ParcelSystem& parcels) {
  int j0 = 0, j1 = 0;
  row_range(parcels, j0, j1);
  const int clear_to = std::max(rows_touched_, j1);
  for (int j = 0; j < clear_to; ++j)
    for (int i = 0; i < grid_.nx(); ++i) alpha_p_(i, j) = 0.0;
  rows_touched_ = j1;
  // Serial in parcel order: the order is thread-independent, so the sums are too.
  for (std::size_t k = 0; k < parcels.size(); ++k) {
    const DepositStencil d = deposit_stencil(grid_, parcels.x[k], parcels.y[k], cfg_.influence_width);
    const double volume = parcels.n_real[k] * particle_volume_;  // eq. (12), per metre of depth
    for (int m = 0; m < d.count; ++m) {
      const int i = d.i[static_cast<std::size_t>(m)], j = d.j[static_cast<std::size_t>(m)];
      alpha_p_(i, j) += d.fraction[static_cast<std::size_t>(m)] * volume / grid_.area(i, j);
    }
  }
  copy_edge_to_ghosts(grid_, alpha_p_, 0, clear_to);
}

void GasParticleCoupling::initialize(GasSolver& gas, ParcelSystem& parcels) {
  const std::size_t n = parcels.size();
  std::int32_t max_id = -1;
  for (std::size_t k = 0; k < n; ++k) max_id = std::max(max_id, parcels.id[k]);
  const auto by_id = static_cast<std::size_t>(max_id + 1);
  samples_.assign(by_id, Sample{});
  for (auto* v : {&impulse_x_, &impulse_y_, &work_, &heat_, &force_x_prev_, &force_y_prev_, &vx_prev_,
                  &vy_prev_, &gas_rotation_, &relative_rotation_, &sampled_p_}) {
    v->assign(by_id, 0.0);
  }
  parcels.external_forces = cfg_.drag || cfg_.magnus || cfg_.pressure_force || cfg_.rotation_torque;
  parcels.integrate_temperature = cfg_.heat_transfer;

  deposit_alpha(parcels);
  if (!cfg_.two_way) return;
  Field2D& alpha = gas.porosity();
  for (int j = 0; j < grid_.ny(); ++j) {
    for (int i = 0; i < grid_.nx(); ++i) {
      const double a = 1.0 - std::min(alpha_p_(i, j), cfg_.max_volume_fraction);
      const double scale = a / alpha(i, j);
      for (int k = 0; k < 4; ++k) gas.conserved(k)(i, j) *= scale;
      alpha(i, j) = a;
    }
  }
  gas.refresh_primitives();
}

void GasParticleCoupling::sample_gas(const GasSolver& gas, const ParcelSystem& parcels, double dt) {
  const GasPrimitives g = gas.primitives();
  int j0 = 0, j1 = 0;
  row_range(parcels, j0, j1);
  if (needs_vorticity()) {
    vorticity_z_rows(grid_, *g.u, *g.v, j0, j1, vorticity_);
    copy_edge_to_ghosts(grid_, vorticity_, j0, j1);
  }
  if (cfg_.pressure_force) {
    gradient_rows(grid_, *g.p, j0, j1, dpdx_, dpdy_);
    copy_edge_to_ghosts(grid_, dpdx_, j0, j1);
    copy_edge_to_ghosts(grid_, dpdy_, j0, j1);
  }
  const std::size_t n = parcels.size();
#pragma omp parallel for schedule(static) if (n >= kParallelParcels)
  for (std::size_t k = 0; k < n; ++k) {
    const InterpolationStencil st = interpolation_stencil(grid_, parcels.x[k], parcels.y[k], cfg_.interpolation);
    Sample s{};
    s.rho = st.apply(*g.rho);
    s.u = st.apply(*g.u);
    s.v = st.apply(*g.v);
    s.p = st.apply(*g.p);
    s.T = st.apply(*g.T);
    const ThermoAt th = thermo_at(gas_cfg_.thermo, s.T);
    const TransportProperties tp = particle_transport(gas_cfg_.transport, s.T, th.cp);
    s.mu = tp.mu;
    s.lambda = tp.lambda;
    s.c = th.c;
    s.cp = th.cp;
    s.alpha_g = 1.0 - std::min(st.apply(alpha_p_), cfg_.max_volume_fraction);
    s.vorticity = needs_vorticity() ? st.apply(vorticity_) : 0.0;
    s.dpdx = cfg_.pressure_force ? st.apply(dpdx_) : 0.0;
    s.dpdy = cfg_.pressure_force ? st.apply(dpdy_) : 0.0;
    // Model coefficients for this CFD step, at the parcel's current slip and spin (Table 1);
    // the sub-steps apply them to the current slip, spin and temperature.
    const double d = dem_cfg_.particle_diameter;
    const double slip = std::hypot(s.u - parcels.vx[k], s.v - parcels.vy[k]);
    const double re = s.rho * slip * d / s.mu;
    if (cfg_.drag) {
      const aero::GasAtParcel at{s.rho, {s.u, s.v}, s.mu, s.c, s.alpha_g};
      s.drag_coef = aero::drag_coefficient(at, slip, d, cfg_.compressibility_correction, cfg_.volume_fraction);
    }
    if (cfg_.magnus) {
      const double c_lm = cfg_.magnus_coefficient * (cfg_.lun_liu ? aero::lun_liu_factor(re) : 1.0);
      s.magnus_coef = c_lm * std::numbers::pi / 8.0 * s.rho * d * d * d;
    }
    if (cfg_.pressure_force) {
      const Vec2 f = aero::pressure_force(d, {s.dpdx, s.dpdy});
      s.pressure_fx = f.x;
      s.pressure_fy = f.y;
    }
    if (cfg_.rotation_torque) {
      // M = kappa w_rel with kappa = M(w_rel0) / w_rel0 (Dennis et al. torque is odd in w_rel).
      const double w0 = aero::relative_rotation(s.vorticity, parcels.omega[k]);
      s.torque_coef = w0 != 0.0 ? aero::rotation_torque(s.rho, s.mu, d, w0, cfg_.torque_stokes_below) / w0
                                : std::numbers::pi * s.mu * d * d * d;  // Stokes slope at w_rel -> 0
    }
    if (cfg_.heat_transfer) {
      s.heat_coef = std::numbers::pi * d * s.lambda * aero::nusselt_ranz_marshall(re, s.mu * s.cp / s.lambda);
    }
    const auto id = static_cast<std::size_t>(parcels.id[k]);
    samples_[id] = s;
    sampled_p_[id] = s.p;
    gas_rotation_[id] = 0.5 * s.vorticity;
    impulse_x_[id] = impulse_y_[id] = work_[id] = heat_[id] = 0.0;
  }
  if (cfg_.two_way) stiff_exchange_relief(gas, parcels, dt);
}

void GasParticleCoupling::stiff_exchange_relief(const GasSolver& gas, const ParcelSystem& ps, double dt) {
  int j0 = 0, j1 = 0;
  row_range(ps, j0, j1);
  for (Field2D* f : {&cell_drag_, &cell_heat_, &cell_mass_, &cell_heat_capacity_}) {
    for (int j = 0; j < j1; ++j)
      for (int i = 0; i < grid_.nx(); ++i) (*f)(i, j) = 0.0;
  }
  // Per-cell sums over the parcels, in parcel order (thread-independent).
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const Sample& s = samples_[static_cast<std::size_t>(ps.id[k])];
    const double kd = ps.n_real[k] * s.drag_coef;
    const double kh = ps.n_real[k] * s.heat_coef;
    const DepositStencil st = deposit_stencil(grid_, ps.x[k], ps.y[k], cfg_.influence_width);
    for (int m = 0; m < st.count; ++m) {
      const int i = st.i[static_cast<std::size_t>(m)], j = st.j[static_cast<std::size_t>(m)];
      const double f = st.fraction[static_cast<std::size_t>(m)];
      cell_drag_(i, j) += f * kd;
      cell_heat_(i, j) += f * kh;
      cell_mass_(i, j) += f * ps.mass[k];
      cell_heat_capacity_(i, j) += f * ps.mass[k] * dem_cfg_.heat_capacity;
    }
  }
  const Field2D& gas_mass_density = gas.conserved(0);  // alpha_g rho
  const GasPrimitives g = gas.primitives();
  for (int j = 0; j < j1; ++j) {
    for (int i = 0; i < grid_.nx(); ++i) {
      if (cell_mass_(i, j) == 0.0) continue;
      const double m_gas = gas_mass_density(i, j) * grid_.area(i, j);
      const ThermoAt th = thermo_at(gas_cfg_.thermo, (*g.T)(i, j));
      const double cv_gas = th.cp / th.gamma;
      cell_drag_(i, j) = 1.0 / (1.0 + dt * cell_drag_(i, j) * (1.0 / m_gas + 1.0 / cell_mass_(i, j)));
      cell_heat_(i, j) =
          1.0 / (1.0 + dt * cell_heat_(i, j) * (1.0 / (m_gas * cv_gas) + 1.0 / cell_heat_capacity_(i, j)));
    }
  }
  for (std::size_t k = 0; k < ps.size(); ++k) {
    Sample& s = samples_[static_cast<std::size_t>(ps.id[k])];
    const DepositStencil st = deposit_stencil(grid_, ps.x[k], ps.y[k], cfg_.influence_width);
    double drag_relief = 0.0, heat_relief = 0.0;
    for (int m = 0; m < st.count; ++m) {
      const int i = st.i[static_cast<std::size_t>(m)], j = st.j[static_cast<std::size_t>(m)];
      const double f = st.fraction[static_cast<std::size_t>(m)];
      drag_relief += f * cell_drag_(i, j);
      heat_relief += f * cell_heat_(i, j);
    }
    s.drag_coef *= drag_relief;
    s.heat_coef *= heat_relief;
  }
}

void GasParticleCoupling::substep_forces(ParcelSystem& ps, double dt_sub, bool first) {
  // Cheap per sub-step: the coefficients were evaluated once per CFD step (sample_gas); here
  // they act on the parcel's current slip, spin and temperature.
  const std::size_t n = ps.size();
  const auto& c = cfg_;
  const double magnus_sign = c.magnus_convention == aero::MagnusConvention::Standard ? 1.0 : -1.0;
#pragma omp parallel for schedule(static) if (n >= kParallelParcels)
  for (std::size_t k = 0; k < n; ++k) {
    const auto id = static_cast<std::size_t>(ps.id[k]);
    const Sample& s = samples_[id];
    // Work of the previous sub-step's exchange force over that sub-step: F . (v^n + v^{n+1})/2,
    // which is exactly the kinetic energy symplectic Euler gave the parcel for it.
    if (!first) {
      work_[id] += (force_x_prev_[id] * 0.5 * (vx_prev_[id] + ps.vx[k]) +
                    force_y_prev_[id] * 0.5 * (vy_prev_[id] + ps.vy[k])) * dt_sub_prev_;
    }
    const Vec2 ur{s.u - ps.vx[k], s.v - ps.vy[k]};
    const double w_rel = aero::relative_rotation(s.vorticity, ps.omega[k]);
    relative_rotation_[id] = w_rel;
    const Vec2 drag = ur * s.drag_coef;
    const Vec2 magnus = cross(magnus_sign * s.magnus_coef * w_rel, ur);  // Table 1, see aero::magnus_force
    ps.drag_fx[k] = drag.x;
    ps.drag_fy[k] = drag.y;
    ps.magnus_fx[k] = magnus.x;
    ps.magnus_fy[k] = magnus.y;
    ps.pressure_fx[k] = s.pressure_fx;
    ps.pressure_fy[k] = s.pressure_fy;
    ps.fluid_torque[k] = s.torque_coef * w_rel;
    const double q = s.heat_coef * (s.T - ps.temperature[k]);
    if (c.heat_transfer) ps.heat_rate[k] = q;
    // Exchange terms (eqs. 13-15): drag + Magnus momentum and heat, per real particle.
    const Vec2 exchange = drag + magnus;
    impulse_x_[id] += exchange.x * dt_sub;
    impulse_y_[id] += exchange.y * dt_sub;
    heat_[id] += q * dt_sub;
    force_x_prev_[id] = exchange.x;
    force_y_prev_[id] = exchange.y;
    vx_prev_[id] = ps.vx[k];
    vy_prev_[id] = ps.vy[k];
  }
  dt_sub_prev_ = dt_sub;
}

void GasParticleCoupling::finish_work(const ParcelSystem& ps) {
  const std::size_t n = ps.size();
#pragma omp parallel for schedule(static) if (n >= kParallelParcels)
  for (std::size_t k = 0; k < n; ++k) {
    const auto id = static_cast<std::size_t>(ps.id[k]);
    work_[id] += (force_x_prev_[id] * 0.5 * (vx_prev_[id] + ps.vx[k]) +
                  force_y_prev_[id] * 0.5 * (vy_prev_[id] + ps.vy[k])) * dt_sub_prev_;
  }
}

void GasParticleCoupling::check_parcels(const ParcelSystem& ps) const {
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const char* bad = nullptr;
    if (!std::isfinite(ps.x[k]) || !std::isfinite(ps.y[k])) bad = "position";
    else if (!std::isfinite(ps.vx[k]) || !std::isfinite(ps.vy[k])) bad = "velocity";
    else if (!std::isfinite(ps.omega[k])) bad = "angular velocity";
    else if (!(ps.temperature[k] > 0.0) || !std::isfinite(ps.temperature[k])) bad = "temperature";
    if (bad != nullptr) {
      std::ostringstream m;
      m << "parcel id " << ps.id[k] << ": " << bad << " not finite (x = " << ps.x[k] << " m, y = " << ps.y[k]
        << " m, vx = " << ps.vx[k] << " m/s, vy = " << ps.vy[k] << " m/s, T = " << ps.temperature[k] << " K)";
      throw NumericalFailure(m.str());
    }
  }
}

void GasParticleCoupling::deposit_exchange(GasSolver& gas, const ParcelSystem& ps, double dt) {
  deposit_alpha(ps);
  const int substeps = exchange_.substeps;
  exchange_ = ExchangeTotals{};
  exchange_.substeps = substeps;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const auto id = static_cast<std::size_t>(ps.id[k]);
    const double nr = ps.n_real[k];
    exchange_.parcel_impulse_x += nr * impulse_x_[id];
    exchange_.parcel_impulse_y += nr * impulse_y_[id];
    exchange_.parcel_work += nr * work_[id];
    exchange_.parcel_heat += nr * heat_[id];
  }
  if (!cfg_.two_way) return;
  src_x_.fill(0.0);
  src_y_.fill(0.0);
  src_e_.fill(0.0);
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const auto id = static_cast<std::size_t>(ps.id[k]);
    const DepositStencil d = deposit_stencil(grid_, ps.x[k], ps.y[k], cfg_.influence_width);
    const double nr = ps.n_real[k];
    for (int m = 0; m < d.count; ++m) {
      const int i = d.i[static_cast<std::size_t>(m)], j = d.j[static_cast<std::size_t>(m)];
      const double w = d.fraction[static_cast<std::size_t>(m)] * nr / (grid_.area(i, j) * dt);
      src_x_(i, j) += w * impulse_x_[id];
      src_y_(i, j) += w * impulse_y_[id];
      src_e_(i, j) += w * (work_[id] + heat_[id]);
    }
  }
  // Porosity update with the p d(alpha_g)/dt work of eq. (3): alpha_g rho and alpha_g rho u
  // are unchanged; the gas is compressed or expanded isentropically by the volume the
  // particles took or gave back. To first order this is exactly -p d(alpha_g); unlike the
  // linear form it cannot drive the internal energy negative when alpha_g changes by a
  // large fraction in one step.
  Field2D& alpha = gas.porosity();
  const Field2D& temperature = *gas.primitives().T;
  const Field2D& mass = gas.conserved(0);
  const Field2D& mom_x = gas.conserved(1);
  const Field2D& mom_y = gas.conserved(2);
  Field2D& energy = gas.conserved(3);
  Field2D* sources[3] = {&gas.source(1), &gas.source(2), &gas.source(3)};
  for (int j = 0; j < grid_.ny(); ++j) {
    for (int i = 0; i < grid_.nx(); ++i) {
      const double a_new = 1.0 - std::min(alpha_p_(i, j), cfg_.max_volume_fraction);
      const double a_old = alpha(i, j);
      if (a_new != a_old) {
        const double kinetic = 0.5 * (mom_x(i, j) * mom_x(i, j) + mom_y(i, j) * mom_y(i, j)) / mass(i, j);
        const double gamma = thermo_at(gas_cfg_.thermo, temperature(i, j)).gamma;
        energy(i, j) = kinetic + (energy(i, j) - kinetic) * std::pow(a_old / a_new, gamma - 1.0);
        alpha(i, j) = a_new;
      }
      (*sources[0])(i, j) = -src_x_(i, j);
      (*sources[1])(i, j) = -src_y_(i, j);
      (*sources[2])(i, j) = -src_e_(i, j);
      const double area_dt = grid_.area(i, j) * dt;
      exchange_.gas_impulse_x += src_x_(i, j) * area_dt;
      exchange_.gas_impulse_y += src_y_(i, j) * area_dt;
      exchange_.gas_energy += src_e_(i, j) * area_dt;
    }
  }
  gas.refresh_primitives();
}

void GasParticleCoupling::advance(GasSolver& gas, ParcelSystem& parcels, double dt) {
  sample_gas(gas, parcels, dt);
  int substep = 0;
  const int n = parcels.substeps_for(dt);
  const double dt_sub = dt / n;
  exchange_.substeps = parcels.advance(dt, [&](ParcelSystem& ps, double) { substep_forces(ps, dt_sub, substep++ == 0); });
  finish_work(parcels);
  check_parcels(parcels);
  deposit_exchange(gas, parcels, dt);
}

}  // namespace dustlift
