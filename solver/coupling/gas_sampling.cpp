// Step 1 of a CFD step: the gas at every stepped parcel (eq. 16), the derived fields the
// models read near the parcels, and the models' coefficients of the sub-step laws.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "solver/core/derivatives.hpp"
#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/coupling/gas_properties.hpp"
#include "solver/coupling/sphere_average.hpp"

namespace dustlift {

void GasParticleCoupling::momentum_fields(const GasPrimitives& g, int j0, int j1, int i1) {
  // clang-format off
#pragma omp parallel for schedule(static) if (static_cast<std::size_t>(j1 - j0) * i1 >= kParallelMinimum)
  // clang-format on
  for (int j = j0; j < j1; ++j) {
    for (int i = 0; i < i1; ++i) {
      rho_u_(i, j) = (*g.rho)(i, j) * (*g.u)(i, j);
      rho_v_(i, j) = (*g.rho)(i, j) * (*g.v)(i, j);
    }
  }
}

void GasParticleCoupling::derived_segment(const GasPrimitives& g, int j, int i0, int i1) {
  const GasReads& r = effects_.reads();
  if (r.rotation) vorticity_z_segment(grid_, *g.u, *g.v, j, i0, i1, vorticity_);
  if (r.pressure_gradient) gradient_segment(grid_, *g.p, j, i0, i1, dpdx_, dpdy_);
  if (r.momentum_gradient) {
    gradient_segment(grid_, rho_u_, j, i0, i1, dx_rho_u_, dy_rho_u_);
    gradient_segment(grid_, rho_v_, j, i0, i1, dx_rho_v_, dy_rho_v_);
  }
}

void GasParticleCoupling::derivatives_near_parcels(const GasPrimitives& g, int j0, int j1, int i1) {
  const GasReads& r = effects_.reads();
  if (!r.rotation && !r.pressure_gradient && !r.momentum_gradient) return;
  const int nx = grid_.nx(), ny = grid_.ny();
  j0 = std::max(j0, 0);
  j1 = std::min(j1, ny);
  i1 = std::min(i1, nx);
  if (j1 <= j0 || i1 <= 0) return;
  // The momentum's derivatives read it one cell around the cells they are made in.
  if (r.momentum_gradient)
    momentum_fields(g, std::max(j0 - 1, 0), std::min(j1 + 1, ny), std::min(i1 + 1, nx));
  // A parcel's interpolation quad lies within one cell of the cell holding its centre, and
  // that cell has alpha_p > 0 (the last deposit was made at the current positions). So the
  // quads read only cells within one cell of a cell with alpha_p > 0: the derivatives are
  // made there and nowhere else (above the layer the lifted parcels are sparse, and a row
  // has few such cells). Each cell's value is the one a full row would give.
  const int last_column = std::min(i1, nx - 1);  // columns up to i1 reach cells below i1
  const std::size_t width = static_cast<std::size_t>(nx) + 2;
  near_scratch_.resize(width * static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
  // clang-format off
#pragma omp parallel for schedule(dynamic, 1) if (static_cast<std::size_t>(j1 - j0) * i1 >= kParallelMinimum)
  // clang-format on
  for (int j = j0; j < j1; ++j) {
    // near[i + 1]: column i holds parcels in one of the rows j-1, j, j+1.
    std::uint8_t* near =
        near_scratch_.data() + width * static_cast<std::size_t>(omp_get_thread_num());
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
      derived_segment(g, j, begin, i);
    }
  }
}

void GasParticleCoupling::average_over_particles(const double* x, const double* y, const double* d,
                                                 std::size_t n, ModelInput* in) const {
  const GasReads& reads = effects_.reads();
  constexpr std::size_t kBatch = 64;
  InterpolationBatch<kBatch> quads =
      slab_ ? InterpolationBatch<kBatch>(*slab_->whole, grid_, slab_->first_column)
            : InterpolationBatch<kBatch>(grid_);
  struct Averaged {
    const Field2D* field;
    double GasSample::*member;
  };
  std::array<Averaged, 8> all{};
  std::size_t count = 0;
  if (reads.pressure_gradient) {
    all[count++] = {&dpdx_, &GasSample::dpdx};
    all[count++] = {&dpdy_, &GasSample::dpdy};
  }
  if (reads.momentum_gradient) {
    all[count++] = {&rho_u_, &GasSample::rho_u};
    all[count++] = {&rho_v_, &GasSample::rho_v};
    all[count++] = {&dx_rho_u_, &GasSample::dx_rho_u};
    all[count++] = {&dy_rho_u_, &GasSample::dy_rho_u};
    all[count++] = {&dx_rho_v_, &GasSample::dx_rho_v};
    all[count++] = {&dy_rho_v_, &GasSample::dy_rho_v};
  }
  const std::span<const Averaged> fields(all.data(), count);
  for (std::size_t q = 0; q < n; ++q)
    for (const Averaged& f : fields) in[q].gas.*f.member = 0.0;
  std::array<double, kBatch> px{}, py{}, value{};
  for (const SpherePoint& s : sphere_points()) {
    for (std::size_t q = 0; q < n; ++q) {
      const double a = 0.5 * d[q];
      px[q] = x[q] + s.xi * a;
      py[q] = y[q] + s.eta * a;
    }
    quads.clear();
    quads.push_points(px.data(), py.data(), n, cfg_.interpolation);
    for (const Averaged& f : fields) {
      quads.apply(*f.field, value.data());
      for (std::size_t q = 0; q < n; ++q) in[q].gas.*f.member += s.weight * value[q];
    }
  }
}

void GasParticleCoupling::sampled_rows(const ParcelSystem& ps, int& j0, int& j1, int& i1) const {
  // The derivatives are needed where the sampled parcels' quads read them: their rows and
  // columns, two cells of margin (the quad and the 3-point stencils).
  const std::size_t active = stepped_.count;
  j0 = 0, j1 = 0, i1 = grid_.nx();
  // A slab makes them in every cell whatever it steps, and row_range is collective there.
  if (active == ps.size() || slab_) {
    row_range(ps, j0, j1);
  } else if (active > 0) {
    j0 = std::max(0, grid_.y().locate(stepped_.y_min) - 2);
    j1 = std::min(grid_.ny(), grid_.y().locate(stepped_.y_max) + 3);
    i1 = std::min(grid_.nx(), grid_.x().locate(stepped_.x_max) + 3);
  } else {
    i1 = 0;
  }
}

void GasParticleCoupling::derived_fields_for_sampling(const GasPrimitives& g, ParcelSystem& ps) {
  int j0 = 0, j1 = 0, i1 = 0;
  sampled_rows(ps, j0, j1, i1);
  const bool momentum = effects_.reads().momentum_gradient;
  if (!slab_ && cfg_.finite_size) {
    // Averages over the particles read the fields across each sphere: whole rows, widened by
    // the largest radius.
    const double reach = 0.5 * largest_diameter_;
    j0 = std::max(0, grid_.y().locate(grid_.y().center(j0) - reach) - 1);
    j1 = std::min(grid_.ny(), grid_.y().locate(grid_.y().center(std::max(j1 - 1, 0)) + reach) + 2);
    if (momentum) momentum_fields(g, j0, j1, grid_.nx());
    for (int j = j0; j < j1; ++j) derived_segment(g, j, 0, grid_.nx());
    for (Field2D* f : derived_) copy_edge_to_ghosts(grid_, *f, j0, j1);
  } else if (!slab_) {
    derivatives_near_parcels(g, j0, j1, i1);
    for (Field2D* f : derived_) copy_edge_to_ghosts(grid_, *f, j0, j1);
  } else {
    // A slab: every cell (the neighbours' parcels read the cut's columns too), then the cut's
    // ghost columns from the neighbours. Each cell's value is the one the whole grid gives.
    const int nx = grid_.nx();
    if (momentum) momentum_fields(g, 0, grid_.ny(), nx);
      // clang-format off
#pragma omp parallel for schedule(static) if (static_cast<std::size_t>(grid_.ny()) * nx >= kParallelMinimum)
    // clang-format on
    for (int j = 0; j < grid_.ny(); ++j) derived_segment(g, j, 0, nx);
    if (!slab_->derived_fields.empty())
      fill_ghosts(grid_, slab(), slab_->derived_fields, 0, grid_.ny());
    // Rank copies are sampled inside the slab (their samples are their owners', refreshed later).
    const std::size_t active = stepped_.count;
    std::vector<double>& sample_x = slab_->sample_x;
    sample_x.assign(ps.x.begin(), ps.x.begin() + static_cast<std::ptrdiff_t>(active));
    const double lo = grid_.x().center(0), hi = grid_.x().center(grid_.nx() - 1);
    for (std::size_t k = 0; k < active; ++k) {
      if (ps.is_rank_copy(k)) sample_x[k] = std::clamp(sample_x[k], lo, hi);
    }
  }
}

void GasParticleCoupling::interpolate_sampled(const InterpolationBatch<kSampleBatch>& quads,
                                              const GasPrimitives& g, std::size_t count,
                                              double (*value)[kSampleBatch]) const {
  const GasReads& r = effects_.reads();
  const Field2D* fields[kSampledFields] = {g.rho,
                                           g.u,
                                           g.v,
                                           g.p,
                                           g.T,
                                           &alpha_p_,
                                           r.rotation ? &vorticity_ : nullptr,
                                           r.pressure_gradient ? &dpdx_ : nullptr,
                                           r.pressure_gradient ? &dpdy_ : nullptr,
                                           r.momentum_gradient ? &dx_rho_u_ : nullptr,
                                           r.momentum_gradient ? &dy_rho_u_ : nullptr,
                                           r.momentum_gradient ? &dx_rho_v_ : nullptr,
                                           r.momentum_gradient ? &dy_rho_v_ : nullptr};
  for (int f = 0; f < kSampledFields; ++f) {
    if (fields[f] != nullptr) {
      quads.apply(*fields[f], value[f]);
    } else {
      std::fill(value[f], value[f] + count, 0.0);
    }
  }
}

void GasParticleCoupling::sample_batch(const GasPrimitives& g, ParcelSystem& ps, std::size_t k0,
                                       std::size_t count, const StepContext& step) const {
  const GasReads& reads = effects_.reads();
  const double* x_sampled = slab_ ? slab_->sample_x.data() : ps.x.data();
  const double* real_d = ps.real_diameter.data();  // each parcel's own real particles
  std::array<ModelInput, kSampleBatch> in;
  // The batch's stencils, then each field at all of them (a vector loop per field).
  InterpolationBatch<kSampleBatch> quads =
      slab_ ? InterpolationBatch<kSampleBatch>(*slab_->whole, grid_, slab_->first_column)
            : InterpolationBatch<kSampleBatch>(grid_);
  quads.push_points(x_sampled + k0, ps.y.data() + k0, count, cfg_.interpolation);
  alignas(64) double value[kSampledFields][kSampleBatch];
  interpolate_sampled(quads, g, count, value);
  for (std::size_t q = 0; q < count; ++q) {
    const std::size_t k = k0 + q;
    const double d = real_d[k];
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
    s.gamma = th.gamma;
    s.alpha_g = 1.0 - std::min(value[kAlphaP][q], cfg_.max_volume_fraction);
    s.vorticity = value[kVorticity][q];
    s.dpdx = value[kDpdx][q];
    s.dpdy = value[kDpdy][q];
    s.dx_rho_u = value[kDxRhoU][q];
    s.dy_rho_u = value[kDyRhoU][q];
    s.dx_rho_v = value[kDxRhoV][q];
    s.dy_rho_v = value[kDyRhoV][q];
    s.rho_u = s.rho * s.u;
    s.rho_v = s.rho * s.v;
    in[q].parcel = ParcelAtSample{ps.vx[k], ps.vy[k], ps.omega[k], d, 1.0 / ps.inv_mass_real[k]};
    const double sx = s.u - ps.vx[k], sy = s.v - ps.vy[k];
    in[q].slip = std::sqrt(sx * sx + sy * sy);
    in[q].re = s.rho * in[q].slip * d / s.mu;
  }
  if (cfg_.finite_size && (reads.pressure_gradient || reads.momentum_gradient))
    average_over_particles(x_sampled + k0, ps.y.data() + k0, real_d + k0, count, in.data());
  effects_.coefficients(in.data(), k0, count, ps, step);
  double* gu = ps.column(col_.gas_u).data();
  double* gv = ps.column(col_.gas_v).data();
  double* grot = ps.column(col_.gas_rotation).data();
  double* gT = ps.column(col_.gas_T).data();
  double* gp = ps.column(col_.gas_p).data();
  for (std::size_t q = 0; q < count; ++q) {
    const std::size_t k = k0 + q;
    const GasSample& s = in[q].gas;
    gu[k] = s.u;
    gv[k] = s.v;
    grot[k] = 0.5 * s.vorticity;  // the fluid spins at half its vorticity
    gT[k] = s.T;
    gp[k] = s.p;
  }
}

void GasParticleCoupling::sample_gas(const GasSolver& gas, ParcelSystem& ps) {
  const GasPrimitives g = gas.primitives();
  derived_fields_for_sampling(g, ps);
  const std::size_t n = stepped_.count;
  const StepContext step{ps.time()};
  // Batches of parcels: each is sampled, then every effect runs over the whole batch (one
  // virtual call per effect and batch). Dynamic scheduling: parcels in disturbed gas cost
  // several times those in uniform gas (whose stencils are uniform and whose drag needs no
  // logarithm), and they sit at one end of the x-ordered parcels. Each parcel's result is its
  // own: any schedule and batching gives the same bits.
  const std::size_t batches = (n + kSampleBatch - 1) / kSampleBatch;
#pragma omp parallel for schedule(dynamic, 8) if (n >= kParallelMinimum)
  for (std::size_t b = 0; b < batches; ++b) {
    const std::size_t k0 = b * kSampleBatch;
    sample_batch(g, ps, k0, std::min(kSampleBatch, n - k0), step);
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

}  // namespace dustlift
