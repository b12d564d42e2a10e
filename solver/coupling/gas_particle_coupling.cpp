#include "solver/coupling/gas_particle_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "solver/core/errors.hpp"
#include "solver/coupling/gas_properties.hpp"

namespace dustlift {

GasParticleCoupling::GasParticleCoupling(const Grid2D& grid, const CouplingConfig& config,
                                         const GasConfig& gas, const DemConfig& dem)
    : grid_(grid),
      cfg_(config),
      dem_cfg_(dem),
      particle_volume_(std::numbers::pi / 6.0 * std::pow(dem.particle_diameter, 3)),
      effects_(config),
      props_(std::make_unique<GasProperties>(gas)),
      stencils_(config.influence_width) {
  largest_diameter_ = dem.particle_diameter;
  for (const PlacedParcel& p : dem.layer_parcels)
    largest_diameter_ = std::max(largest_diameter_, p.particle_diameter);
  for (const SizeClass& c : dem.size_classes) {
    class_volume_.push_back(std::numbers::pi / 6.0 * std::pow(c.diameter, 3));
    largest_diameter_ = std::max(largest_diameter_, c.diameter);
  }
  make_fields();
}

GasParticleCoupling::~GasParticleCoupling() = default;

void GasParticleCoupling::make_fields() {
  alpha_p_ = Field2D(grid_);
  alpha_g_ = Field2D(grid_, 1.0);
  // Only the derived fields a model reads.
  if (effects_.reads().rotation) vorticity_ = Field2D(grid_);
  if (effects_.reads().pressure_gradient) {
    dpdx_ = Field2D(grid_);
    dpdy_ = Field2D(grid_);
  }
  if (effects_.reads().momentum_gradient) {
    for (Field2D* f : {&rho_u_, &rho_v_, &dx_rho_u_, &dy_rho_u_, &dx_rho_v_, &dy_rho_v_})
      *f = Field2D(grid_);
  }
  exchange_.assign(grid_.size_with_ghosts(), ExchangeCell{});
  implicit_.assign(grid_.size_with_ghosts(), ImplicitExchangeCell{});
  derived_ = derived_fields();
  make_slab_fields();
}

void GasParticleCoupling::make_slab_fields() {
  if (slab_ && cfg_.two_way) {
    slab_->drag_factor = Field2D(grid_);
    slab_->heat_factor = Field2D(grid_);
  }
}

void GasParticleCoupling::restore_carried_state(const CarriedState& s) {
  if (s.alpha_p.size() != alpha_p_.size() || s.rows_touched < 0 || s.rows_touched > grid_.ny()) {
    throw std::invalid_argument("GasParticleCoupling: carried state does not fit the grid");
  }
  alpha_p_.raw() = s.alpha_p;
  rows_touched_ = s.rows_touched;
  resting_.restore_reference(s.rest_p, s.rest_T);
  stencils_.invalidate();        // the parcels were replaced: make the stencils anew
  last_reach_ = grid_.nx() - 1;  // and deposit into every column once
}

void GasParticleCoupling::set_slab(const Grid2D& whole, int first_column, GasHalo& halo,
                                   const Communicator& comm) {
  slab_.emplace();
  slab_->whole = &whole;
  slab_->first_column = first_column;
  slab_->halo = &halo;
  slab_->comm = &comm;
  // The fields a slab makes in every cell and exchanges (members: their addresses stay).
  slab_->derived_fields = derived_fields();
  make_slab_fields();
}

std::vector<Field2D*> GasParticleCoupling::derived_fields() {
  std::vector<Field2D*> f;
  if (effects_.reads().rotation) f.push_back(&vorticity_);
  if (effects_.reads().pressure_gradient) {
    f.push_back(&dpdx_);
    f.push_back(&dpdy_);
  }
  if (effects_.reads().momentum_gradient) {
    for (Field2D* d : {&dx_rho_u_, &dy_rho_u_, &dx_rho_v_, &dy_rho_v_}) f.push_back(d);
  }
  return f;
}

void GasParticleCoupling::move_to_slab(const Grid2D& slab, int first_column, GasHalo& halo) {
  grid_ = slab;
  slab_->first_column = first_column;
  slab_->halo = &halo;
  make_fields();
  stencils_.invalidate();
  stencils_.drop_plan();
  deposit_columns_ = 0;
}

void GasParticleCoupling::row_range(const ParcelSystem& parcels, int& j0, int& j1) const {
  double ymin = grid_.y().end(), ymax = grid_.y().start();
  const std::size_t n = parcels.size();
  const double* y = parcels.y.data();
  // clang-format off
#pragma omp parallel for schedule(static) reduction(min : ymin) reduction(max : ymax) if (n >= kParallelMinimum)
  // clang-format on
  for (std::size_t i = 0; i < n; ++i) {
    ymin = std::min(ymin, y[i]);
    ymax = std::max(ymax, y[i]);
  }
  // On several ranks the rows of all parcels: the rows the sources are written in are then
  // the one-rank run's (a cell without parcels there gets -0, as there).
  if (slab_) {
    ymin = -slab_->max(-ymin);
    ymax = slab_->max(ymax);
  }
  // Two rows of margin: the interpolation quad and the 3-point derivative stencils.
  j0 = std::max(0, grid_.y().locate(ymin) - 2);
  j1 = std::min(grid_.ny(), grid_.y().locate(ymax) + 3);
}

void GasParticleCoupling::initialize(GasSolver& gas, ParcelSystem& parcels) {
  // Columns a later step reads for parcels it does not sample again (resting parcels: the
  // implicit exchange's sums, the band filters' rotations, the rest counts) are carried into
  // checkpoints, so that a restart continues bitwise also when skipping within
  // run.rest_tolerance.
  struct Spec {
    ParcelColumn Columns::*column;
    const char *name, *unit;
    bool carried;
  };
  static constexpr Spec kColumns[] = {
      {&Columns::gas_u, "gas_u", "m/s", false},
      {&Columns::gas_v, "gas_v", "m/s", false},
      {&Columns::gas_rotation, "gas_rotation", "rad/s", true},
      {&Columns::gas_T, "gas_temperature", "K", false},
      {&Columns::gas_p, "gas_pressure", "Pa", true},
      {&Columns::rest_steps, "rest_steps", "1", true},
      {&Columns::stepped, "stepped", "1", false},
      {&Columns::impulse_x, "exchange_impulse_x", "N s", false},
      {&Columns::impulse_y, "exchange_impulse_y", "N s", false},
      {&Columns::work, "exchange_work", "J", false},
      {&Columns::heat, "exchange_heat", "J", false},
      {&Columns::relative_rotation, "relative_rotation", "rad/s", true}};
  for (const Spec& s : kColumns)
    col_.*s.column = parcels.attach_column({s.name, s.unit, s.carried, false});
  effects_.attach(parcels);
  stiff_sampled_.clear();
  for (const StiffCoefficient& c : effects_.stiff_momentum()) stiff_sampled_.push_back(c.sampled);
  for (const StiffCoefficient& c : effects_.stiff_heat()) stiff_sampled_.push_back(c.sampled);
  // The DEM's sub-steps apply the effects' laws (a gas that moves no parcel sets nothing).
  if (!effects_.empty()) {
    parcels.set_forcing(
        effects_.forcing({col_.gas_u, col_.gas_v, col_.gas_rotation, col_.gas_T, col_.impulse_x,
                          col_.impulse_y, col_.work, col_.heat, col_.relative_rotation}));
  }
  parcels.store_parts_on_last_substep_only(true);
  parcels.set_stepped_column(col_.stepped);
  parcels.build_neighbours_if_due();

  deposit_alpha(parcels);  // no stencils yet: every column
  if (!cfg_.two_way) return;
  for (int j = 0; j < grid_.ny(); ++j)
    for (int i = 0; i < grid_.nx(); ++i)
      alpha_g_(i, j) = 1.0 - std::min(alpha_p_(i, j), cfg_.max_volume_fraction);
  gas.initialize_porosity(alpha_g_);
}

FlowEnvelope GasParticleCoupling::flow_envelope(const GasSolver& gas) const {
  double d = dem_cfg_.particle_diameter;
  for (const SizeClass& c : dem_cfg_.size_classes) d = std::max(d, c.diameter);
  const GasPrimitives g = gas.primitives();
  FlowEnvelope e;
  for (int j = 0; j < grid_.ny(); ++j) {
    for (int i = 0; i < grid_.nx(); ++i) {
      e.max_volume_fraction = std::max(e.max_volume_fraction, alpha_p_(i, j));
      const double T = (*g.T)(i, j), rho = (*g.rho)(i, j);
      const double speed = std::hypot((*g.u)(i, j), (*g.v)(i, j));
      const GasProperties::At th = props_->thermo(T);
      const double mu = props_->transport(T, th.cp).mu;
      e.max_reynolds = std::max(e.max_reynolds, rho * speed * d / mu);
      e.max_mach = std::max(e.max_mach, speed / th.c);
    }
  }
  if (const CouplingSlab* s = slab()) {
    e.max_volume_fraction = s->max(e.max_volume_fraction);
    e.max_reynolds = s->max(e.max_reynolds);
    e.max_mach = s->max(e.max_mach);
  }
  return e;
}

void GasParticleCoupling::check_parcels(const ParcelSystem& ps) const {
  const std::size_t n = ps.size();
  std::size_t first_bad = n;
#pragma omp parallel for schedule(static) reduction(min : first_bad) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    if (ps.is_rank_copy(k)) continue;  // its owner checks it
    const bool ok = std::isfinite(ps.x[k]) && std::isfinite(ps.y[k]) && std::isfinite(ps.vx[k]) &&
                    std::isfinite(ps.vy[k]) && std::isfinite(ps.omega[k]) &&
                    ps.temperature[k] > 0.0 && std::isfinite(ps.temperature[k]);
    if (!ok) first_bad = std::min(first_bad, k);
  }
  std::string local;
  if (first_bad != n) {
    const std::size_t k = first_bad;
    const char* bad = !std::isfinite(ps.x[k]) || !std::isfinite(ps.y[k])     ? "position"
                      : !std::isfinite(ps.vx[k]) || !std::isfinite(ps.vy[k]) ? "velocity"
                      : !std::isfinite(ps.omega[k])                          ? "angular velocity"
                                                                             : "temperature";
    std::ostringstream m;
    m << "parcel id " << ps.id[k] << ": " << bad << " not finite (x = " << ps.x[k]
      << " m, y = " << ps.y[k] << " m, vx = " << ps.vx[k] << " m/s, vy = " << ps.vy[k]
      << " m/s, T = " << ps.temperature[k] << " K)";
    local = m.str();
  }
  // On several ranks every rank stops with the same message.
  const std::string failure = slab() != nullptr ? slab()->first_failure(local) : local;
  if (!failure.empty()) throw NumericalFailure(failure);
}

void GasParticleCoupling::advance(GasSolver& gas, ParcelSystem& parcels, double dt) {
  {
    const ScopedTimer t(timings_.sample);
    stepped_ = resting_.plan(gas, parcels, dt, grid_, slab(), {col_.rest_steps, col_.stepped},
                             cfg_.influence_width, skip_resting_);
    sample_gas(gas, parcels);
  }
  if (cfg_.two_way) {
    const ScopedTimer t(timings_.implicit_exchange);
    // The factors sum every parcel's sampled coefficients, rank copies' included (their owners').
    if (parcels.decomposed()) parcels.refresh_rank_copies(stiff_sampled_);
    apply_implicit_exchange(gas, parcels, dt);
  }
  last_substeps_ = parcels.advance(dt);
  const ScopedTimer t(timings_.deposit);
  // The deposit sums every parcel's exchange, rank copies' included.
  if (cfg_.two_way && parcels.decomposed()) {
    const ParcelColumn exchanged[] = {col_.impulse_x, col_.impulse_y, col_.work, col_.heat};
    parcels.refresh_rank_copies(exchanged);
  }
  check_parcels(parcels);
  deposit_exchange(gas, parcels, dt);
}

}  // namespace dustlift
