// The gas solver: SLAU2 + MUSCL, porosity-weighted fluxes (docs/gas-solver.md), central
// viscous terms, SSP-RK3 (Shu-Osher), ghost-cell boundaries. See docs/gas-solver.md. This
// file: construction, the initial state, the primitives from the conserved state, and access
// to the state; gas_solver_impl.hpp names the files of the other parts.
#include <cmath>
#include <stdexcept>

#include "solver/gas/gas_solver_impl.hpp"
#include "solver/gas/shock_relations.hpp"

namespace dustlift {

namespace {

GasThermo make_thermo(const ThermoConfig& c) {
  if (c.model == ThermoModel::CaloricallyPerfect)
    return CaloricallyPerfectGas(c.gamma, c.gas_constant);
  return ThermallyPerfectAir(c.gas_constant);
}

}  // namespace

GasSolver::Impl::Impl(const Grid2D& g, const GasConfig& c)
    : grid(g),
      config(c),
      thermo(make_thermo(c.thermo)),
      muscl(muscl_settings(c.scheme)),
      viscous(c.transport.model != TransportModel::Inviscid),
      nx(g.nx()),
      ny(g.ny()),
      ng(g.ghosts()),
      stride(g.stride()),
      threaded(g.interior_cells() >= kMinCellsForThreads),
      R(c.thermo.gas_constant),
      skip_resting(c.skip_resting_cells && !c.has_gravity()) {
  if (ng < 2) throw std::invalid_argument("GasSolver: the grid needs at least 2 ghost layers");
  if (nx < 1 || ny < 1) throw std::invalid_argument("GasSolver: the grid has no cells");
  for (int k = 0; k < Conserved::kCount; ++k) {
    U[k] = Field2D(grid);
    U0[k] = Field2D(grid);
    source[k] = Field2D(grid);
    fx[k].assign(static_cast<std::size_t>(nx + 1) * ny, 0.0);
    fy[k].assign(static_cast<std::size_t>(nx) * (ny + 1), 0.0);
  }
  fx_pressure.assign(static_cast<std::size_t>(nx + 1) * ny, 0.0);
  fy_pressure.assign(static_cast<std::size_t>(nx) * (ny + 1), 0.0);
  y_face_owner.assign(static_cast<std::size_t>(ny + 1), -1);
  x_face_owner.assign(static_cast<std::size_t>(ny), -1);
  row_lo.assign(static_cast<std::size_t>(ny), 0);
  row_hi.assign(static_cast<std::size_t>(ny), nx);
  rest_agreement.whole_columns = nx;
  whole_lo.assign(static_cast<std::size_t>(ny), 0);
  whole_hi.assign(static_cast<std::size_t>(ny), nx);
  rest_to.assign(static_cast<std::size_t>(ny + 2 * ng), -ng - 1);
  rest_from.assign(static_cast<std::size_t>(ny + 2 * ng), nx + ng);
  suffix_cache.suffix.assign(static_cast<std::size_t>(ny + 2 * ng), 0);
  suffix_cache.dirty_to.assign(static_cast<std::size_t>(ny + 2 * ng), nx + 2 * ng);
  source_rows.assign(static_cast<std::size_t>(ny), SourceExtent{});
  source_row_bound = ny;
  source_column_bound = nx;
  saved_lo.assign(static_cast<std::size_t>(ny), 0);
  widened_lo_.assign(static_cast<std::size_t>(ny), 0);
  widened_hi_.assign(static_cast<std::size_t>(ny), 0);
  saved_hi.assign(static_cast<std::size_t>(ny), 0);
  rho = Field2D(grid, 1.0);
  u = Field2D(grid);
  v = Field2D(grid);
  p = Field2D(grid, 1.0);
  T = Field2D(grid, 300.0);
  alpha = Field2D(grid, 1.0);
  mu = Field2D(grid);
  lambda = Field2D(grid);
  build_geometry(grid.x(), inv_dx, inv_dxc, inv_dx2);
  build_geometry(grid.y(), inv_dy, inv_dyc, inv_dy2);
  fault_i.assign(static_cast<std::size_t>(ny), -1);
  fault_kind.assign(static_cast<std::size_t>(ny), CellFault::None);
  make_boundaries({});
  ensure_scratch();
}

void GasSolver::Impl::build_geometry(const Axis& a, std::vector<double>& inv_w,
                                     std::vector<double>& inv_c, std::vector<double>& inv_2) {
  const int n = a.cells(), g = a.ghosts();
  inv_w.assign(static_cast<std::size_t>(n + 2 * g), 0.0);
  inv_c = inv_w;
  inv_2 = inv_w;
  for (int i = -g; i < n + g; ++i) {
    const auto k = static_cast<std::size_t>(i + g);
    inv_w[k] = 1.0 / a.width(i);
    if (i + 1 < n + g) inv_c[k] = 1.0 / (a.center(i + 1) - a.center(i));
    if (i - 1 >= -g && i + 1 < n + g) inv_2[k] = 1.0 / (a.center(i + 1) - a.center(i - 1));
  }
}

/// Sets cell (i, j) to state s: the primitives exactly as given (T as the scene gave it, or
/// p/(rho R)), the conserved variables from them. A state at rest then has exactly the same
/// p and T in every cell whatever the porosity, so it stays at rest to the last bit.
template <class Th>
void GasSolver::Impl::set_cell_state(const Th& th, int i, int j, const PrimitiveState& s) {
  const std::size_t c = at(i, j);
  const double a = alpha.data()[c];
  const double t = temperature_of(s, R);
  U[Conserved::kMass].data()[c] = a * s.rho;
  U[Conserved::kMomentumX].data()[c] = a * s.rho * s.u;
  U[Conserved::kMomentumY].data()[c] = a * s.rho * s.v;
  U[Conserved::kEnergy].data()[c] =
      a * s.rho * (th.internal_energy(t) + 0.5 * (s.u * s.u + s.v * s.v));
  rho.data()[c] = s.rho;
  u.data()[c] = s.u;
  v.data()[c] = s.v;
  p.data()[c] = s.p;
  T.data()[c] = t;
}

template <class Th>
void GasSolver::Impl::initialize(const Th& th, const InitialCondition& ic) {
  state_written();
  fill_porosity_ghosts();
  PrimitiveState below = ic.left, above = ic.right;
  if (ic.kind == InitialCondition::Kind::Shock) {
    below = normal_shock(ic.state, ic.mach, config.thermo, ic.axis).post;
    above = ic.state;
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      PrimitiveState s = ic.state;
      if (ic.kind != InitialCondition::Kind::Uniform) {
        const double coord = ic.axis == 'y' ? grid.y().center(j) : grid.x().center(i);
        s = coord < ic.position ? below : above;
      }
      set_cell_state(th, i, j, s);
    }
  }
  record_inflow_states();  // also fills the ghosts
}

template <class Th>
void GasSolver::Impl::refresh(const Th& th) {
  suffix_cache.valid = false;
  fill_porosity_ghosts();
#pragma omp parallel if (threaded)
  {
#pragma omp for schedule(static)
    for (int j = 0; j < ny; ++j) {
      const StageScratch sc = stage_scratch();
      for (int i = 0; i < nx; ++i) sc.changed[i] = 1.0;
      (void)primitives_row(th, primitive_row(j, 0, nx), sc);
    }
    fill_local_ghosts();
  }
  fill_collective_ghosts();
}

GasSolver::GasSolver(const Grid2D& grid, const GasConfig& config)
    : impl_(std::make_unique<Impl>(grid, config)) {
  // Until initialize(): a uniform state at rest so that every accessor is valid.
  initialize(InitialCondition{});
}

GasSolver::~GasSolver() = default;

GasSolver::GasSolver(GasSolver&&) noexcept = default;

GasSolver& GasSolver::operator=(GasSolver&&) noexcept = default;

void GasSolver::initialize(const InitialCondition& ic) {
  std::visit([&](const auto& th) { impl_->initialize(th, ic); }, impl_->thermo);
}

const Grid2D& GasSolver::grid() const {
  return impl_->grid;
}

const GasConfig& GasSolver::config() const {
  return impl_->config;
}

GasPrimitives GasSolver::primitives() const {
  return {&impl_->rho, &impl_->u, &impl_->v, &impl_->p, &impl_->T, &impl_->alpha};
}

GasTotals GasSolver::totals() const {
  GasTotals t;
  const Impl& m = *impl_;
  for (int j = 0; j < m.ny; ++j) {
    GasTotals row;
    for (int i = 0; i < m.nx; ++i) {
      const double area = m.grid.area(i, j);
      row.mass += m.U[Conserved::kMass](i, j) * area;
      row.momentum_x += m.U[Conserved::kMomentumX](i, j) * area;
      row.momentum_y += m.U[Conserved::kMomentumY](i, j) * area;
      row.energy += m.U[Conserved::kEnergy](i, j) * area;
    }
    t.mass += row.mass;
    t.momentum_x += row.momentum_x;
    t.momentum_y += row.momentum_y;
    t.energy += row.energy;
  }
  return t;
}

double GasSolver::sound_speed(int i, int j) const {
  const double t = impl_->T(i, j);
  return std::visit([&](const auto& th) { return std::sqrt(th.sound_speed_squared(t)); },
                    impl_->thermo);
}

Field2D& GasSolver::conserved(int k) {
  impl_->state_written();
  return impl_->U[static_cast<std::size_t>(k)];
}

const Field2D& GasSolver::conserved(int k) const {
  return impl_->U[static_cast<std::size_t>(k)];
}

void GasSolver::refresh_primitives() {
  std::visit([&](const auto& th) { impl_->refresh(th); }, impl_->thermo);
}

Field2D& GasSolver::porosity() {
  impl_->state_written();
  return impl_->alpha;
}

long long GasSolver::cell_updates() const {
  return impl_->cell_updates;
}

Field2D& GasSolver::source(int k) {
  // Whoever writes through the reference may write anywhere.
  impl_->source_row_bound = impl_->ny;
  impl_->source_column_bound = impl_->nx;
  return impl_->source[static_cast<std::size_t>(k)];
}

const Field2D& GasSolver::source(int k) const {
  return impl_->source[static_cast<std::size_t>(k)];
}

void GasSolver::sources_zero_beyond(int rows, int columns) {
  Impl& m = *impl_;
  m.source_row_bound = std::clamp(rows, 0, m.ny);
  m.source_column_bound = std::clamp(columns, 0, m.nx);
}

SourceBounds GasSolver::source_bounds() const {
  return {impl_->source_row_bound, impl_->source_column_bound};
}

Field2D& GasSolver::primitive_field(int k) {
  Impl& m = *impl_;
  m.state_written();
  Field2D* fields[Primitive::kCount] = {&m.rho, &m.u, &m.v, &m.p, &m.T};
  if (k < 0 || k >= Primitive::kCount)
    throw std::out_of_range("GasSolver::primitive_field: k must be 0..4");
  return *fields[k];
}

}  // namespace dustlift
