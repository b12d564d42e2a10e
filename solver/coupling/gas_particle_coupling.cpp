#include "solver/coupling/gas_particle_coupling.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <sstream>
#include <stdexcept>

#include "solver/core/derivatives.hpp"
#include "solver/core/errors.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/gas/rest_ranges.hpp"
#include "solver/gas/thermo.hpp"
#include "solver/gas/transport.hpp"

namespace dustlift {

/// cp(T), c(T) and gamma(T) of the configured thermodynamics, and the transport properties
/// the particle models use: the gas's own (the Gordon-Wilke model through the same table as
/// the gas solver), or for an inviscid gas the Gordon-Wilke air values (the gas itself stays
/// inviscid; the particles always need mu and lambda).
class GasParticleCoupling::GasProperties {
 public:
  explicit GasProperties(const GasConfig& g)
      : thermo_(g.thermo), transport_(g.transport), perfect_(g.thermo.gamma, g.thermo.gas_constant),
        air_(g.thermo.gas_constant) {}
  struct At {
    double cp, c, gamma;
  };
  At thermo(double T) const {
    if (thermo_.model == ThermoModel::CaloricallyPerfect) {
      return {perfect_.cp(T), std::sqrt(perfect_.sound_speed_squared(T)), perfect_.gamma(T)};
    }
    const double cp = air_.cp(T), R = thermo_.gas_constant;
    const double gamma = cp / (cp - R);
    return {cp, std::sqrt(gamma * R * T), gamma};
  }
  TransportProperties transport(double T, double cp) const {
    if (transport_.model == TransportModel::Inviscid || transport_.model == TransportModel::GordonWilke) return table_(T);
    return transport_properties(transport_, T, cp);
  }

 private:
  ThermoConfig thermo_;
  TransportConfig transport_;
  CaloricallyPerfectGas perfect_;
  ThermallyPerfectAir air_;
  GordonWilkeAirTable table_;
};

namespace {

void copy_edge_to_ghosts(const Grid2D& g, Field2D& f, int j0, int j1, bool left = true, bool right = true) {
  // Zero-gradient ghost values so that interpolation next to the boundary sees the edge cell
  // (at the domain's own ends: a slab's cut columns come from its neighbour).
  const int ng = g.ghosts();
  for (int j = std::max(j0, 0); j < std::min(j1, g.ny()); ++j) {
    for (int k = 1; k <= ng; ++k) {
      if (left) f(-k, j) = f(0, j);
      if (right) f(g.nx() - 1 + k, j) = f(g.nx() - 1, j);
    }
  }
  for (int i = -ng; i < g.nx() + ng; ++i) {
    for (int k = 1; k <= ng; ++k) {
      if (j0 <= 0) f(i, -k) = f(i, 0);
      if (j1 >= g.ny()) f(i, g.ny() - 1 + k) = f(i, g.ny() - 1);
    }
  }
}

/// Resets columns [0, columns) of rows [0, rows) of the interior of a per-cell array
/// (indexed as the grid's fields) to T{}.
template <class T>
void clear_rows(const Grid2D& g, T* cells, int rows, int columns) {
  const int nx = std::min(columns, g.nx()), n_rows = std::min(rows, g.ny());
  if (nx <= 0) return;
#pragma omp parallel for schedule(static) if (static_cast<std::size_t>(n_rows) * nx >= kParallelMinimum)
  for (int j = 0; j < n_rows; ++j) std::fill_n(cells + g.index(0, j), nx, T{});
}

}  // namespace

GasParticleCoupling::GasParticleCoupling(const Grid2D& grid, const CouplingConfig& config,
                                         const GasConfig& gas, const DemConfig& dem)
    : grid_(grid), cfg_(config), gas_cfg_(gas), dem_cfg_(dem),
      particle_volume_(std::numbers::pi / 6.0 * std::pow(dem.particle_diameter, 3)),
      models_(config), props_(std::make_unique<GasProperties>(gas)), alpha_p_(grid), alpha_g_(grid, 1.0),
      exchange_(grid.size_with_ghosts()), relief_(grid.size_with_ghosts()) {
  if (models_.reads().rotation) vorticity_ = Field2D(grid);
  if (models_.reads().pressure_gradient) {
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
  rest_p_ = s.rest_p;
  rest_T_ = s.rest_T;
  stencil_dem_steps_ = -1;  // the parcels were replaced: make the stencils anew
  last_reach_ = grid_.nx() - 1;  // and deposit into every column once
}

GasParticleCoupling::~GasParticleCoupling() = default;

void GasParticleCoupling::set_slab(const Grid2D& whole, int first_column, GasHalo& halo) {
  whole_ = &whole;
  first_column_ = first_column;
  halo_ = &halo;
  // The fields a slab makes in every cell and exchanges (members: their addresses stay).
  derived_fields_.clear();
  if (models_.reads().rotation) derived_fields_.push_back(&vorticity_);
  if (models_.reads().pressure_gradient) {
    derived_fields_.push_back(&dpdx_);
    derived_fields_.push_back(&dpdy_);
  }
  if (cfg_.two_way) {
    relief_drag_ = Field2D(grid_);
    relief_heat_ = Field2D(grid_);
  }
}

void GasParticleCoupling::move_to_slab(const Grid2D& slab, int first_column, GasHalo& halo) {
  grid_ = slab;
  first_column_ = first_column;
  halo_ = &halo;
  alpha_p_ = Field2D(grid_);
  alpha_g_ = Field2D(grid_, 1.0);
  if (models_.reads().rotation) vorticity_ = Field2D(grid_);
  if (models_.reads().pressure_gradient) {
    dpdx_ = Field2D(grid_);
    dpdy_ = Field2D(grid_);
  }
  exchange_.assign(grid_.size_with_ghosts(), ExchangeCell{});
  relief_.assign(grid_.size_with_ghosts(), ReliefCell{});
  if (cfg_.two_way) {
    relief_drag_ = Field2D(grid_);
    relief_heat_ = Field2D(grid_);
  }
  stencil_dem_steps_ = -1;
  planned_parcels_ = 0;
  deposit_columns_ = 0;
}

void GasParticleCoupling::fill_ghosts(std::span<Field2D* const> fields, int j0, int j1) {
  const bool left = halo_ == nullptr || halo_->owns_left_boundary();
  const bool right = halo_ == nullptr || halo_->owns_right_boundary();
  for (Field2D* f : fields) copy_edge_to_ghosts(grid_, *f, j0, j1, left, right);
  if (halo_ != nullptr) halo_->exchange_columns(fields);
}

void GasParticleCoupling::row_range(const ParcelSystem& parcels, int& j0, int& j1) const {
  double ymin = grid_.y().end(), ymax = grid_.y().start();
  const std::size_t n = parcels.size();
  const double* y = parcels.y.data();
#pragma omp parallel for schedule(static) reduction(min : ymin) reduction(max : ymax) if (n >= kParallelMinimum)
  for (std::size_t i = 0; i < n; ++i) {
    ymin = std::min(ymin, y[i]);
    ymax = std::max(ymax, y[i]);
  }
  // On several ranks the rows of all parcels: the rows the sources are written in are then
  // the one-rank run's (a cell without parcels there gets -0, as there).
  if (parcels.decomposed()) {
    ymin = -parcels.max_over_ranks(-ymin);
    ymax = parcels.max_over_ranks(ymax);
  }
  // Two rows of margin: the interpolation quad and the 3-point derivative stencils.
  j0 = std::max(0, grid_.y().locate(ymin) - 2);
  j1 = std::min(grid_.ny(), grid_.y().locate(ymax) + 3);
}

bool GasParticleCoupling::stencils_need_all(const ParcelSystem& parcels) const {
  return stencil_dem_steps_ < 0 || stencils_.size() != parcels.size() ||
         parcels.data_permutations() != stencil_permutations_;
}

void GasParticleCoupling::update_stencils(const ParcelSystem& parcels, std::size_t count) {
  const bool all = stencils_need_all(parcels);
  if (!all && stencil_dem_steps_ == parcels.steps()) return;  // no DEM step since: current
  const std::size_t n = parcels.size();
  // Parcels from `count` on did not move since their stencils were made (the caller's count
  // covers every parcel stepped since), and no re-sort moved them to other indices.
  const std::size_t end = all ? n : std::min(count, n);
  stencils_.resize(n);
  const double w = cfg_.influence_width;
  constexpr std::size_t kBlock = 1024;
  const std::size_t blocks = (end + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) if (end >= kParallelMinimum)
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t k0 = b * kBlock;
    const std::size_t count = std::min(kBlock, end - k0);
    deposit_stencils(whole_ != nullptr ? *whole_ : grid_, parcels.x.data() + k0, parcels.y.data() + k0, w,
                     stencils_.data() + k0, count);
    // On a slab: the whole grid's columns as the slab's (the neighbour's cells fall outside
    // [0, nx) and are skipped by the deposits).
    if (whole_ != nullptr) {
      for (std::size_t k = k0; k < k0 + count; ++k) {
        for (int m = 0; m < stencils_[k].count; ++m) stencils_[k].i[static_cast<std::size_t>(m)] -= first_column_;
      }
    }
  }
  stencil_dem_steps_ = parcels.steps();
  stencil_permutations_ = parcels.data_permutations();
  planned_parcels_ = 0;  // the deposit plan was for the old stencils
}

void GasParticleCoupling::plan_scatter(std::size_t count) {
  // A plan over more parcels serves too (the passes skip the columns they do not fill).
  if (planned_parcels_ >= count && planned_parcels_ > 0) return;
  scatter_.plan(stencils_, count, grid_.nx(), kParallelMinimum);
  planned_parcels_ = count;
}

int GasParticleCoupling::deposit_column_bound(double x) const {
  // A stencil's square [x0, x0 + w] with x0 >= x - w/2 clipped at the start (deposit_stencil,
  // grid_transfer.hpp).
  const double right = std::max(x + 0.5 * std::max(cfg_.influence_width, 0.0),
                                grid_.x().start() + cfg_.influence_width);
  return std::min(grid_.nx() - 1, grid_.x().locate(right) + 1);
}

std::size_t GasParticleCoupling::parcels_reaching(const ParcelSystem& ps, int column) const {
  const std::size_t n = ps.size();
  // Near the right end a clipped square reaches further left than x - w/2: take all.
  if (column >= grid_.nx() - 2) return n;
  const double half = 0.5 * std::max(cfg_.influence_width, 0.0);
  const double face = grid_.x().face(column + 1);
  const double* x = ps.x.data();
  std::size_t last = 0;
#pragma omp parallel for schedule(static) reduction(max : last) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    if (x[k] - half <= face) last = std::max(last, k + 1);
  }
  return last;
}

void GasParticleCoupling::deposit_alpha(const ParcelSystem& parcels) {
  int j0 = 0, j1 = 0;
  row_range(parcels, j0, j1);
  const int clear_to = std::max(rows_touched_, j1);
  rows_touched_ = j1;
  cleared_to_ = clear_to;
  // Only columns [0, C] can change: those the parcels stepped this step reached before and
  // after it, and those the last deposit changed (their sources go back to zero). Beyond C
  // every cell's parcels rested and kept their order, so its sums are the ones it holds. A
  // re-sort, or no stencils yet, makes everything anew.
  const std::size_t stepped = last_active_;
  int reach = grid_.nx() - 1;
  if (!stencils_need_all(parcels) && stepped < parcels.size()) {
    double x_after = -std::numeric_limits<double>::infinity();
    const double* x = parcels.x.data();
#pragma omp parallel for schedule(static) reduction(max : x_after) if (stepped >= kParallelMinimum)
    for (std::size_t k = 0; k < stepped; ++k) x_after = std::max(x_after, x[k]);
    reach = stepped == 0 ? 0 : deposit_column_bound(std::max(active_x_max_, x_after));
  }
  const int c = std::min(std::max(reach, last_reach_), grid_.nx() - 1);
  last_reach_ = reach;
  deposit_columns_ = c;
  const std::size_t reaching = parcels_reaching(parcels, c);
  clear_rows(grid_, alpha_p_.data(), clear_to, c + 1);
  update_stencils(parcels, reaching);
  plan_scatter(reaching);
  // Each cell sums its parcels in parcel order whatever the thread count (ParallelDeposit).
  const double* n_real = parcels.n_real.data();
  scatter_.run(stencils_, [&](std::size_t k, int m) {
    const DepositStencil& d = stencils_[k];
    const int i = d.i[static_cast<std::size_t>(m)], j = d.j[static_cast<std::size_t>(m)];
    if (i > c) return;
    const double volume = n_real[k] * particle_volume_;  // eq. (12), per metre of depth
    alpha_p_(i, j) += d.fraction[static_cast<std::size_t>(m)] * volume / grid_.area(i, j);
  });
  Field2D* const deposited[] = {&alpha_p_};
  fill_ghosts(deposited, 0, clear_to);
}

void GasParticleCoupling::initialize(GasSolver& gas, ParcelSystem& parcels) {
  auto attach = [&](const char* name, const char* unit) { return parcels.attach_column({name, unit, false, false}); };
  // Columns a later step reads for parcels it does not sample again (resting parcels: the
  // relief's sums, the band filters' rotations, the rest counts) go into checkpoints, so that
  // a restart continues bitwise also when skipping within run.rest_tolerance.
  auto carried = [&](const char* name, const char* unit) { return parcels.attach_column({name, unit, true, false}); };
  col_.gas_u = attach("gas_u", "m/s");
  col_.gas_v = attach("gas_v", "m/s");
  col_.gas_rotation = carried("gas_rotation", "rad/s");
  col_.gas_T = attach("gas_temperature", "K");
  col_.gas_p = carried("gas_pressure", "Pa");
  col_.drag_raw = carried("drag_coefficient_sampled", "N s/m");
  col_.heat_raw = carried("heat_coefficient_sampled", "W/K");
  col_.rest_steps = carried("rest_steps", "1");
  col_.active = attach("stepped", "1");
  col_.drag = attach("drag_coefficient", "N s/m");
  col_.magnus = attach("magnus_coefficient", "N s^2/m^2");
  col_.torque = attach("torque_coefficient", "N m s");
  col_.heat_coef = attach("heat_coefficient", "W/K");
  col_.impulse_x = attach("exchange_impulse_x", "N s");
  col_.impulse_y = attach("exchange_impulse_y", "N s");
  col_.work = attach("exchange_work", "J");
  col_.heat = attach("exchange_heat", "J");
  col_.relative_rotation = carried("relative_rotation", "rad/s");
  // The sub-step effects are what the models write.
  const ForceParts& parts = models_.writes();
  forcing_.drag = parts.drag;
  forcing_.magnus = parts.magnus;
  forcing_.pressure = parts.pressure;
  forcing_.torque = parts.torque;
  forcing_.heat = parts.heat;
  forcing_.gas_u = col_.gas_u;
  forcing_.gas_v = col_.gas_v;
  forcing_.gas_rotation = col_.gas_rotation;
  forcing_.gas_temperature = col_.gas_T;
  forcing_.drag_coefficient = col_.drag;
  forcing_.magnus_coefficient = col_.magnus;
  forcing_.torque_coefficient = col_.torque;
  forcing_.heat_coefficient = col_.heat_coef;
  forcing_.impulse_x = col_.impulse_x;
  forcing_.impulse_y = col_.impulse_y;
  forcing_.work = col_.work;
  forcing_.heat_in = col_.heat;
  forcing_.relative_rotation = col_.relative_rotation;
  parcels.set_gas_forcing(forcing_);
  parcels.store_parts_on_last_substep_only(true);
  parcels.set_activity_column(col_.active);
  parcels.build_neighbours_if_due();

  deposit_alpha(parcels);  // no stencils yet: every column
  if (!cfg_.two_way) return;
  for (int j = 0; j < grid_.ny(); ++j)
    for (int i = 0; i < grid_.nx(); ++i) alpha_g_(i, j) = 1.0 - std::min(alpha_p_(i, j), cfg_.max_volume_fraction);
  gas.initialize_porosity(alpha_g_);
}

void GasParticleCoupling::derivatives_near_parcels(const GasPrimitives& g, int j0, int j1, int i1) {
  const bool vorticity = models_.reads().rotation, gradient = models_.reads().pressure_gradient;
  if (!vorticity && !gradient) return;
  const int nx = grid_.nx(), ny = grid_.ny();
  j0 = std::max(j0, 0);
  j1 = std::min(j1, ny);
  i1 = std::min(i1, nx);
  if (j1 <= j0 || i1 <= 0) return;
  // A parcel's interpolation quad lies within one cell of the cell holding its centre, and
  // that cell has alpha_p > 0 (the last deposit was made at the current positions). So the
  // quads read only cells within one cell of a cell with alpha_p > 0: the derivatives are
  // made there and nowhere else (above the layer the lifted parcels are sparse, and a row
  // has few such cells). Each cell's value is the one a full row would give.
  const int last_column = std::min(i1, nx - 1);  // columns up to i1 reach cells below i1
  const std::size_t width = static_cast<std::size_t>(nx) + 2;
  near_scratch_.resize(width * static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
#pragma omp parallel for schedule(dynamic, 1) if (static_cast<std::size_t>(j1 - j0) * i1 >= kParallelMinimum)
  for (int j = j0; j < j1; ++j) {
    // near[i + 1]: column i holds parcels in one of the rows j-1, j, j+1.
    std::uint8_t* near = near_scratch_.data() + width * static_cast<std::size_t>(omp_get_thread_num());
    std::fill(near, near + width, std::uint8_t{0});
    for (int r = std::max(j - 1, 0); r <= std::min(j + 1, ny - 1); ++r) {
      const double* a = &alpha_p_(0, r);
      for (int i = 0; i <= last_column; ++i) near[i + 1] |= static_cast<std::uint8_t>(a[i] > 0.0);
    }
    // Runs of cells i with parcels in columns i-1..i+1.
    int i = 0;
    while (i < i1) {
      while (i < i1 && (near[i] | near[i + 1] | near[i + 2]) == 0) ++i;
      const int begin = i;
      while (i < i1 && (near[i] | near[i + 1] | near[i + 2]) != 0) ++i;
      if (i == begin) break;
      if (vorticity) vorticity_z_segment(grid_, *g.u, *g.v, j, begin, i, vorticity_);
      if (gradient) gradient_segment(grid_, *g.p, j, begin, i, dpdx_, dpdy_);
    }
  }
}

void GasParticleCoupling::sample_gas(const GasSolver& gas, ParcelSystem& ps, std::size_t active) {
  const GasPrimitives g = gas.primitives();
  // The derivatives are needed where the sampled parcels' quads read them: their rows and
  // columns, two cells of margin (the quad and the 3-point stencils).
  int j0 = 0, j1 = 0, i1 = grid_.nx();
  // A slab makes them in every cell whatever it steps, and row_range is collective there.
  if (active == ps.size() || halo_ != nullptr) {
    row_range(ps, j0, j1);
  } else if (active > 0) {
    j0 = std::max(0, grid_.y().locate(active_y_min_) - 2);
    j1 = std::min(grid_.ny(), grid_.y().locate(active_y_max_) + 3);
    i1 = std::min(grid_.nx(), grid_.x().locate(active_x_max_) + 3);
  } else {
    i1 = 0;
  }
  if (halo_ == nullptr) {
    derivatives_near_parcels(g, j0, j1, i1);
    if (models_.reads().rotation) copy_edge_to_ghosts(grid_, vorticity_, j0, j1);
    if (models_.reads().pressure_gradient) {
      copy_edge_to_ghosts(grid_, dpdx_, j0, j1);
      copy_edge_to_ghosts(grid_, dpdy_, j0, j1);
    }
  } else {
    // A slab: every cell (the neighbours' parcels read the cut's columns too), then the cut's
    // ghost columns from the neighbours. Each cell's value is the one the whole grid gives.
    const int nx = grid_.nx();
#pragma omp parallel for schedule(static) if (static_cast<std::size_t>(grid_.ny()) * nx >= kParallelMinimum)
    for (int j = 0; j < grid_.ny(); ++j) {
      if (models_.reads().rotation) vorticity_z_segment(grid_, *g.u, *g.v, j, 0, nx, vorticity_);
      if (models_.reads().pressure_gradient) gradient_segment(grid_, *g.p, j, 0, nx, dpdx_, dpdy_);
    }
    if (!derived_fields_.empty()) fill_ghosts(derived_fields_, 0, grid_.ny());
    // Ghosts are sampled inside the slab (their samples are their owners', refreshed later).
    sample_x_.assign(ps.x.begin(), ps.x.begin() + static_cast<std::ptrdiff_t>(active));
    const double lo = grid_.x().center(0), hi = grid_.x().center(grid_.nx() - 1);
    for (std::size_t k = 0; k < active; ++k) {
      if (ps.is_ghost(k)) sample_x_[k] = std::clamp(sample_x_[k], lo, hi);
    }
  }
  const double* x_sampled = halo_ != nullptr ? sample_x_.data() : ps.x.data();
  const std::size_t n = active;
  double* gu = ps.column(col_.gas_u).data();
  double* gv = ps.column(col_.gas_v).data();
  double* grot = ps.column(col_.gas_rotation).data();
  double* gT = ps.column(col_.gas_T).data();
  double* gp = ps.column(col_.gas_p).data();
  double* K_raw = ps.column(col_.drag_raw).data();
  double* H_raw = ps.column(col_.heat_raw).data();
  double* K = ps.column(col_.drag).data();
  double* M = ps.column(col_.magnus).data();
  double* kappa = ps.column(col_.torque).data();
  double* H = ps.column(col_.heat_coef).data();
  const double d = dem_cfg_.particle_diameter;
  const bool vort = models_.reads().rotation;
  // Batches of parcels: each is sampled, then every model runs over the whole batch (one
  // virtual call per model and batch). Dynamic scheduling: parcels in disturbed gas cost
  // several times those in uniform gas (whose stencils are uniform and whose drag needs no
  // logarithm), and they sit at one end of the x-ordered parcels. Each parcel's result is its
  // own: any schedule and batching gives the same bits.
  constexpr std::size_t kBatch = 64;
  const std::size_t batches = (n + kBatch - 1) / kBatch;
  const bool pressure = models_.reads().pressure_gradient;
#pragma omp parallel for schedule(dynamic, 8) if (n >= kParallelMinimum)
  for (std::size_t b = 0; b < batches; ++b) {
    std::array<ModelInput, kBatch> in;
    std::array<SubstepCoefficients, kBatch> out{};
    const std::size_t k0 = b * kBatch, count = std::min(kBatch, n - k0);
    // The batch's stencils, then each field at all of them (a vector loop per field).
    InterpolationBatch<kBatch> quads =
        whole_ != nullptr ? InterpolationBatch<kBatch>(*whole_, grid_, first_column_) : InterpolationBatch<kBatch>(grid_);
    quads.push_points(x_sampled + k0, ps.y.data() + k0, count, cfg_.interpolation);
    enum Sampled { kRho, kU, kV, kP, kT, kAlphaP, kVorticity, kDpdx, kDpdy, kFields };
    alignas(64) double value[kFields][kBatch];
    const Field2D* fields[kFields] = {g.rho, g.u, g.v, g.p, g.T, &alpha_p_, vort ? &vorticity_ : nullptr,
                                      pressure ? &dpdx_ : nullptr, pressure ? &dpdy_ : nullptr};
    for (int f = 0; f < kFields; ++f) {
      if (fields[f] != nullptr) {
        quads.apply(*fields[f], value[f]);
      } else {
        std::fill(value[f], value[f] + count, 0.0);
      }
    }
    for (std::size_t q = 0; q < count; ++q) {
      const std::size_t k = k0 + q;
      GasSample& s = in[q].gas;
      s.rho = value[kRho][q];
      s.u = value[kU][q];
      s.v = value[kV][q];
      s.p = value[kP][q];
      s.T = value[kT][q];
      const GasProperties::At th = props_->thermo(s.T);
      const TransportProperties tp = props_->transport(s.T, th.cp);
      s.mu = tp.mu;
      s.lambda = tp.lambda;
      s.c = th.c;
      s.cp = th.cp;
      s.alpha_g = 1.0 - std::min(value[kAlphaP][q], cfg_.max_volume_fraction);
      s.vorticity = value[kVorticity][q];
      s.dpdx = value[kDpdx][q];
      s.dpdy = value[kDpdy][q];
      in[q].parcel = ParcelAtSample{ps.vx[k], ps.vy[k], ps.omega[k], d};
      const double sx = s.u - ps.vx[k], sy = s.v - ps.vy[k];
      in[q].slip = std::sqrt(sx * sx + sy * sy);
      in[q].re = s.rho * in[q].slip * d / s.mu;
    }
    models_.coefficients(in.data(), out.data(), count);
    for (std::size_t q = 0; q < count; ++q) {
      const std::size_t k = k0 + q;
      const GasSample& s = in[q].gas;
      const SubstepCoefficients& c = out[q];
      gu[k] = s.u;
      gv[k] = s.v;
      grot[k] = 0.5 * s.vorticity;  // the fluid spins at half its vorticity
      gT[k] = s.T;
      gp[k] = s.p;
      K_raw[k] = K[k] = c.drag;
      M[k] = c.magnus;
      kappa[k] = c.torque;
      H_raw[k] = H[k] = c.heat;
      ps.pressure_fx[k] = c.pressure_fx;
      ps.pressure_fy[k] = c.pressure_fy;
    }
  }
  // Every parcel starts the step with nothing exchanged (the resting ones exchange nothing).
  double* exchanged[] = {ps.column(col_.impulse_x).data(), ps.column(col_.impulse_y).data(),
                         ps.column(col_.work).data(), ps.column(col_.heat).data()};
  const std::size_t all = ps.size();
#pragma omp parallel for schedule(static) if (all >= kParallelMinimum)
  for (std::size_t k = 0; k < all; ++k) {
    for (double* c : exchanged) c[k] = 0.0;
  }
}

void GasParticleCoupling::stiff_exchange_relief(const GasSolver& gas, ParcelSystem& ps, double dt,
                                                std::size_t active) {
  int j0 = 0, j1 = 0;
  row_range(ps, j0, j1);
  update_stencils(ps, ps.size());  // current since the last deposit, unless there was none
  // The stepped parcels read the cells of columns [0, c]; those sum every parcel reaching them.
  const int c = active < ps.size() ? (active == 0 ? -1 : deposit_column_bound(active_x_max_)) : grid_.nx() - 1;
  const std::size_t reaching = c < 0 ? 0 : parcels_reaching(ps, c);
  clear_rows(grid_, relief_.data(), j1, c + 1);
  plan_scatter(reaching);
  const double* K_raw = ps.column(col_.drag_raw).data();
  const double* H_raw = ps.column(col_.heat_raw).data();
  double* K = ps.column(col_.drag).data();
  double* H = ps.column(col_.heat_coef).data();
  // Per-cell sums over all parcels (the resting ones' samples are current), each in parcel
  // order (thread-independent).
  const double c_p = dem_cfg_.heat_capacity;
  const double* n_real = ps.n_real.data();
  const double* mass = ps.mass.data();
  scatter_.run(stencils_, [&](std::size_t k, int m) {
    const DepositStencil& st = stencils_[k];
    const int i = st.i[static_cast<std::size_t>(m)], j = st.j[static_cast<std::size_t>(m)];
    if (i > c) return;
    const double f = st.fraction[static_cast<std::size_t>(m)];
    ReliefCell& r = relief_[grid_.index(i, j)];
    r.drag += f * (n_real[k] * K_raw[k]);
    r.heat += f * (n_real[k] * H_raw[k]);
    r.mass += f * mass[k];
    r.heat_capacity += f * mass[k] * c_p;
  });
  const Field2D& gas_mass_density = gas.conserved(0);  // alpha_g rho
  const GasPrimitives g = gas.primitives();
  const int nx = c + 1;
  // Rows one at a time: the cells holding parcels are mostly in the layer's few rows at the
  // bottom, which a static split gave to one thread. Every cell on its own.
#pragma omp parallel for schedule(dynamic, 1) if (static_cast<std::size_t>(j1) * nx >= kParallelMinimum)
  for (int j = 0; j < j1; ++j) {
    for (int i = 0; i < nx; ++i) {
      ReliefCell& r = relief_[grid_.index(i, j)];
      if (r.mass == 0.0) continue;
      const double m_gas = gas_mass_density(i, j) * grid_.area(i, j);
      const GasProperties::At th = props_->thermo((*g.T)(i, j));
      const double cv_gas = th.cp / th.gamma;
      r.drag = 1.0 / (1.0 + dt * r.drag * (1.0 / m_gas + 1.0 / r.mass));
      r.heat = 1.0 / (1.0 + dt * r.heat * (1.0 / (m_gas * cv_gas) + 1.0 / r.heat_capacity));
    }
  }
  if (halo_ != nullptr) {
    // A parcel at the cut reads the neighbour's factors too.
    for (int j = 0; j < j1; ++j) {
      for (int i = 0; i < grid_.nx(); ++i) {
        relief_drag_(i, j) = relief_[grid_.index(i, j)].drag;
        relief_heat_(i, j) = relief_[grid_.index(i, j)].heat;
      }
    }
    Field2D* const factors[] = {&relief_drag_, &relief_heat_};
    fill_ghosts(factors, 0, j1);
    const int ng = grid_.ghosts();
    for (int j = 0; j < j1; ++j) {
      for (int k = 1; k <= ng; ++k) {
        for (const int i : {-k, grid_.nx() - 1 + k}) {
          relief_[grid_.index(i, j)].drag = relief_drag_(i, j);
          relief_[grid_.index(i, j)].heat = relief_heat_(i, j);
        }
      }
    }
  }
  const std::size_t n = active;
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    if (ps.is_ghost(k)) continue;  // its owner's (a ghost's stencil may leave the slab)
    const DepositStencil& st = stencils_[k];
    double drag_relief = 0.0, heat_relief = 0.0;
    for (int m = 0; m < st.count; ++m) {
      const int i = st.i[static_cast<std::size_t>(m)], j = st.j[static_cast<std::size_t>(m)];
      const double f = st.fraction[static_cast<std::size_t>(m)];
      const ReliefCell& r = relief_[grid_.index(i, j)];
      drag_relief += f * r.drag;
      heat_relief += f * r.heat;
    }
    K[k] *= drag_relief;
    H[k] *= heat_relief;
  }
}

void GasParticleCoupling::check_parcels(const ParcelSystem& ps) const {
  const std::size_t n = ps.size();
  std::size_t first_bad = n;
#pragma omp parallel for schedule(static) reduction(min : first_bad) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    if (ps.is_ghost(k)) continue;  // its owner checks it
    const bool ok = std::isfinite(ps.x[k]) && std::isfinite(ps.y[k]) && std::isfinite(ps.vx[k]) &&
                    std::isfinite(ps.vy[k]) && std::isfinite(ps.omega[k]) && ps.temperature[k] > 0.0 &&
                    std::isfinite(ps.temperature[k]);
    if (!ok) first_bad = std::min(first_bad, k);
  }
  std::string local;
  if (first_bad != n) {
    const std::size_t k = first_bad;
  const char* bad = !std::isfinite(ps.x[k]) || !std::isfinite(ps.y[k])    ? "position"
                    : !std::isfinite(ps.vx[k]) || !std::isfinite(ps.vy[k]) ? "velocity"
                    : !std::isfinite(ps.omega[k])                          ? "angular velocity"
                                                                           : "temperature";
    std::ostringstream m;
    m << "parcel id " << ps.id[k] << ": " << bad << " not finite (x = " << ps.x[k] << " m, y = " << ps.y[k]
      << " m, vx = " << ps.vx[k] << " m/s, vy = " << ps.vy[k] << " m/s, T = " << ps.temperature[k] << " K)";
    local = m.str();
  }
  // On several ranks every rank stops with the same message.
  const std::string failure = ps.first_failure(local);
  if (!failure.empty()) throw NumericalFailure(failure);
}

void GasParticleCoupling::deposit_exchange(GasSolver& gas, const ParcelSystem& ps, double dt) {
  deposit_alpha(ps);  // also makes the stencils at the new positions
  last_dt_ = dt;
  if (!cfg_.two_way) return;
  const double* jx = ps.column(col_.impulse_x).data();
  const double* jy = ps.column(col_.impulse_y).data();
  const double* work = ps.column(col_.work).data();
  const double* heat = ps.column(col_.heat).data();
  // Columns beyond deposit_columns_ had no source last step and have none now (only stepped
  // parcels exchange anything).
  const int columns = deposit_columns_ + 1;
  clear_rows(grid_, exchange_.data(), rows_touched_, columns);
  const double* n_real = ps.n_real.data();
  scatter_.run(stencils_, [&](std::size_t k, int m) {
    const double energy = work[k] + heat[k];
    // A parcel that exchanged nothing adds nothing (skipping it keeps -0 out of the sums).
    if (jx[k] == 0.0 && jy[k] == 0.0 && energy == 0.0) return;
    const DepositStencil& d = stencils_[k];
    const int i = d.i[static_cast<std::size_t>(m)], j = d.j[static_cast<std::size_t>(m)];
    if (i >= columns) return;
    const double w = d.fraction[static_cast<std::size_t>(m)] * n_real[k] / (grid_.area(i, j) * dt);
    ExchangeCell& e = exchange_[grid_.index(i, j)];
    e.x += w * jx[k];
    e.y += w * jy[k];
    e.energy += w * energy;
  });
  const int rows = rows_touched_;
  const int nx = columns;
  Field2D& sx = gas.source(1);
  Field2D& sy = gas.source(2);
  Field2D& se = gas.source(3);
  // Rows [rows, cleared) held parcels before and none now: their sources go back to zero;
  // rows above them never held any. Every cell on its own: any split over threads.
#pragma omp parallel for schedule(static) if (static_cast<std::size_t>(cleared_to_) * nx >= kParallelMinimum)
  for (int j = 0; j < cleared_to_; ++j) {
    for (int i = 0; i < nx; ++i) {
      alpha_g_(i, j) = 1.0 - std::min(alpha_p_(i, j), cfg_.max_volume_fraction);
      if (j >= rows) {
        sx(i, j) = sy(i, j) = se(i, j) = 0.0;
        continue;
      }
      const ExchangeCell& e = exchange_[grid_.index(i, j)];
      sx(i, j) = -e.x;
      sy(i, j) = -e.y;
      se(i, j) = -e.energy;
    }
  }
  gas.change_porosity(alpha_g_, 0, cleared_to_);
}

ExchangeTotals GasParticleCoupling::last_exchange(const ParcelSystem& ps) const {
  ExchangeTotals e;
  e.substeps = last_substeps_;
  const double* jx = ps.column(col_.impulse_x).data();
  const double* jy = ps.column(col_.impulse_y).data();
  const double* work = ps.column(col_.work).data();
  const double* heat = ps.column(col_.heat).data();
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const double nr = ps.n_real[k];
    e.parcel_impulse_x += nr * jx[k];
    e.parcel_impulse_y += nr * jy[k];
    e.parcel_work += nr * work[k];
    e.parcel_heat += nr * heat[k];
  }
  if (!cfg_.two_way) return e;
  for (int j = 0; j < rows_touched_; ++j) {
    for (int i = 0; i < grid_.nx(); ++i) {
      const double area_dt = grid_.area(i, j) * last_dt_;
      const ExchangeCell& cell = exchange_[grid_.index(i, j)];
      e.gas_impulse_x += cell.x * area_dt;
      e.gas_impulse_y += cell.y * area_dt;
      e.gas_energy += cell.energy * area_dt;
    }
  }
  return e;
}

void GasParticleCoupling::resting_on_slab(const GasSolver& gas, const ParcelSystem& ps) {
  // The whole grid's reference: the last cell of the last slab (-inf elsewhere, so that a max
  // over the ranks gives the last rank's values).
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  const bool last = halo_->owns_right_boundary();
  const RestReference own = last ? gas.rest_reference() : RestReference{};
  double reference[6] = {last ? (own.valid ? 1.0 : 0.0) : kNone, last ? own.p : kNone, last ? own.T : kNone,
                         last ? own.du : kNone, last ? own.dp : kNone, last ? own.dT : kNone};
  ps.max_over_ranks(reference);
  RestReference whole;
  whole.valid = reference[0] > 0.5;
  whole.p = reference[1];
  whole.T = reference[2];
  whole.du = reference[3];
  whole.dp = reference[4];
  whole.dT = reference[5];
  gas.resting_gas(resting_, whole);
  // Per row, the first whole-grid column from which the row rests to the domain's end: the
  // largest of the ranks' own (a slab's scan runs to its ghost columns, the neighbour's first
  // cells; one whose interior rests from its first column on defers to the ranks before it,
  // and the first rank counts its boundary ghosts as one rank does).
  const int ny = grid_.ny();
  rest_rows_.resize(static_cast<std::size_t>(ny));
  const bool first = halo_->owns_left_boundary();
  for (int j = 0; j < ny; ++j) {
    const int local = resting_.first_resting[static_cast<std::size_t>(j)];
    rest_rows_[static_cast<std::size_t>(j)] =
        !first && local <= 0 ? kNone : static_cast<double>(first_column_ + local);
  }
  ps.max_over_ranks(rest_rows_);
  for (int j = 0; j < ny; ++j) {
    resting_.first_resting[static_cast<std::size_t>(j)] =
        static_cast<int>(rest_rows_[static_cast<std::size_t>(j)]);
  }
}

std::size_t GasParticleCoupling::plan_active_parcels(const GasSolver& gas, ParcelSystem& ps,
                                                     double dt) {
  const std::size_t n = ps.size();
  double* rest_steps = ps.column(col_.rest_steps).data();
  double* active = ps.column(col_.active).data();
  std::size_t limit = n;
  // On a slab every rank takes part (its collectives), parcels or not.
  if (skip_resting_ && (n > 0 || halo_ != nullptr)) {
    if (halo_ == nullptr) {
      gas.resting_gas(resting_);
    } else {
      resting_on_slab(gas, ps);
    }
    // The counts hold for one reference state: a new one starts them again.
    const RestReference& ref = resting_.reference;
    if (!ref.valid || ref.p != rest_p_ || ref.T != rest_T_) {
      std::fill(rest_steps, rest_steps + n, 0.0);
      rest_p_ = ref.p;
      rest_T_ = ref.T;
    }
    // The gas over a parcel's interpolation quad and derivative stencils (two cells each way)
    // rests when every row j-2..j+2 (j its row) rests from column i-2 on (i its column), that
    // is, when x >= face(first_resting + 2) of each of those rows: one threshold per row
    // window, and one for all rows, so that most resting parcels need no locate at all.
    // On a slab first_resting is in the whole grid's columns (resting_on_slab).
    const int* first_resting = resting_.first_resting.data();
    const int ny = grid_.ny();
    const Axis& ax = whole_ != nullptr ? whole_->x() : grid_.x();
    const int nx = ax.cells();
    auto row_threshold = [&](int r) {
      const int column = first_resting[r] + 2;  // locate(x) >= column <=> x >= face(column)
      if (column <= 0) return -std::numeric_limits<double>::infinity();
      if (column >= nx) return std::numeric_limits<double>::infinity();
      return ax.face(column);
    };
    rest_x_threshold_.resize(static_cast<std::size_t>(ny));
    double all_rows = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < ny; ++j) {
      double t = -std::numeric_limits<double>::infinity();
      for (int r = std::max(j - 2, 0); r <= std::min(j + 2, ny - 1); ++r) t = std::max(t, row_threshold(r));
      rest_x_threshold_[static_cast<std::size_t>(j)] = t;
      all_rows = std::max(all_rows, t);
    }
    const double* threshold = rest_x_threshold_.data();
    const bool valid = ref.valid;
    const double T_ref = ref.T, dT = ref.dT, du = ref.du;
    double front = -std::numeric_limits<double>::infinity(), v_max = 0.0, d_max = 0.0;
#pragma omp parallel for schedule(static) reduction(max : front, v_max, d_max) if (n >= kParallelMinimum)
    for (std::size_t k = 0; k < n; ++k) {
      bool rests = valid && std::abs(ps.temperature[k] - T_ref) <= dT;
      if (rests) {
        const ParcelMotion motion{ps.vx[k],         ps.vy[k],         ps.omega[k],
                                  ps.radius[k],     ps.contact_fx[k], ps.contact_fy[k],
                                  ps.contact_torque[k], ps.mass[k] / ps.n_real[k], ps.inertia[k] / ps.n_real[k]};
        rests = parcel_still(motion, du, dt);
      }
      if (rests && !(ps.x[k] >= all_rows)) rests = ps.x[k] >= threshold[grid_.y().locate(ps.y[k])];
      rest_steps[k] = rests ? rest_steps[k] + 1.0 : 0.0;
      // Two steps: the last step was then a full step at rest, so its stored force parts and
      // samples are exactly what this step would give.
      if (rest_steps[k] < 2.0) front = std::max(front, ps.x[k]);
      v_max = std::max(v_max, std::sqrt(ps.vx[k] * ps.vx[k] + ps.vy[k] * ps.vy[k]));
      d_max = std::max(d_max, ps.diameter[k]);
    }
    if (halo_ != nullptr) {
      // A push from a moving parcel of any rank may reach this rank's parcels: the front and
      // the speeds of all ranks.
      double maxima[3] = {front, v_max, d_max};
      ps.max_over_ranks(maxima);
      front = maxima[0];
      v_max = maxima[1];
      d_max = maxima[2];
    }
    if (front == -std::numeric_limits<double>::infinity()) {
      limit = 0;  // everything rests
    } else {
      // Within one CFD step a push travels one contact per sub-step, parcels move v dt, and a
      // parcel's samples read the alpha_p and gas of cells within two cells of it.
      const int i_front = ax.locate(front);
      double cell = 0.0;
      for (int i = std::max(i_front - 4, 0); i <= std::min(i_front + 12, nx - 1); ++i) {
        cell = std::max(cell, ax.width(i));
      }
      const double reach = (ps.substeps_for(dt) + 2) * d_max + 2.0 * v_max * dt + 4.0 * cell + cfg_.influence_width;
      const double cut = front + reach;
      std::size_t last = 0;
#pragma omp parallel for schedule(static) reduction(max : last) if (n >= kParallelMinimum)
      for (std::size_t k = 0; k < n; ++k) {
        if (rest_steps[k] < 2.0 || ps.x[k] <= cut) last = std::max(last, k + 1);
      }
      limit = last;
    }
  }
  // Where the stepped parcels are: the passes of this step need only the cells they reach.
  double x_max = -std::numeric_limits<double>::infinity(), y_min = grid_.y().end(), y_max = grid_.y().start();
  const double* px = ps.x.data();
  const double* py = ps.y.data();
#pragma omp parallel for schedule(static) reduction(max : x_max, y_max) reduction(min : y_min) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    active[k] = k < limit ? 1.0 : 0.0;
    if (k < limit) {
      x_max = std::max(x_max, px[k]);
      y_min = std::min(y_min, py[k]);
      y_max = std::max(y_max, py[k]);
    }
  }
  active_x_max_ = x_max;
  active_y_min_ = y_min;
  active_y_max_ = y_max;
  last_active_ = limit;
  return limit;
}

void GasParticleCoupling::advance(GasSolver& gas, ParcelSystem& parcels, double dt) {
  std::size_t active = parcels.size();
  {
    const ScopedTimer t(timings_.sample);
    active = plan_active_parcels(gas, parcels, dt);
    sample_gas(gas, parcels, active);
  }
  if (cfg_.two_way) {
    const ScopedTimer t(timings_.relief);
    // The relief sums every parcel's sampled coefficients, ghosts' included (their owners').
    if (parcels.decomposed()) {
      const ParcelColumn sampled[] = {col_.drag_raw, col_.heat_raw};
      parcels.refresh_ghost_columns(sampled);
    }
    stiff_exchange_relief(gas, parcels, dt, active);
  }
  last_substeps_ = parcels.advance(dt);
  const ScopedTimer t(timings_.deposit);
  // The deposit sums every parcel's exchange, ghosts' included.
  if (cfg_.two_way && parcels.decomposed()) {
    const ParcelColumn exchanged[] = {col_.impulse_x, col_.impulse_y, col_.work, col_.heat};
    parcels.refresh_ghost_columns(exchanged);
  }
  check_parcels(parcels);
  deposit_exchange(gas, parcels, dt);
}

}  // namespace dustlift
