#include "solver/gas/boundary_fillers.hpp"

#include <algorithm>

namespace dustlift {
namespace {

/// The interior cell, counted across from the side's own end, that ghost layer g mirrors.
int mirror_cell(int g, int n) {
  return std::min(g, n - 1);
}

/// Counted from the side's own end (0 the cell next to it) into an index across.
int from_end(const SideCells& s, int k) {
  return s.low ? k : s.n - 1 - k;
}

/// The primitive fields' arrays.
struct PrimitiveArrays {
  double* rho;
  double* u;
  double* v;
  double* p;
  double* T;
};
PrimitiveArrays arrays(const PrimitiveGhosts& g) {
  return {g.fields[Primitive::kDensity]->data(), g.fields[Primitive::kVelocityX]->data(),
          g.fields[Primitive::kVelocityY]->data(), g.fields[Primitive::kPressure]->data(),
          g.fields[Primitive::kTemperature]->data()};
}

/// Cell dst takes the state of cell src, its u and v times su and sv.
void copy_state(const PrimitiveArrays& f, std::size_t dst, std::size_t src, double su, double sv) {
  f.rho[dst] = f.rho[src];
  f.u[dst] = su * f.u[src];
  f.v[dst] = sv * f.v[src];
  f.p[dst] = f.p[src];
  f.T[dst] = f.T[src];
}

/// Ghost layer g of every line of this thread's share takes the value of cell from(g) across.
template <class From>
void copy_layers(Field2D& field, const SideCells& s, From from) {
  double* const a = field.data();
#pragma omp for schedule(static) nowait
  for (int line = s.line_begin; line < s.line_end; ++line) {
    for (int g = 0; g < s.ghosts; ++g) a[s.cell(line, s.ghost(g))] = a[s.cell(line, from(g))];
  }
}

}  // namespace

BoundaryKind boundary_kind(const BoundaryConfig& b, GridSide side) {
  switch (side) {
    case GridSide::Left:
      return b.left;
    case GridSide::Right:
      return b.right;
    case GridSide::Bottom:
      return b.bottom;
    default:
      return b.top;
  }
}

SideCells::SideCells(GridSide side, const Grid2D& grid)
    : low(side == GridSide::Left || side == GridSide::Bottom),
      n(is_x_side(side) ? grid.nx() : grid.ny()),
      ghosts(grid.ghosts()),
      line_begin(is_x_side(side) ? 0 : -grid.ghosts()),
      line_end(is_x_side(side) ? grid.ny() : grid.nx() + grid.ghosts()),
      origin(static_cast<std::ptrdiff_t>(grid.ghosts()) * grid.stride() + grid.ghosts()),
      along(is_x_side(side) ? grid.stride() : 1),
      across(is_x_side(side) ? 1 : grid.stride()) {}

PhysicalBoundary::PhysicalBoundary(GridSide side, BoundaryKind kind, const Grid2D& grid,
                                   double gas_constant, std::vector<PrimitiveState> inflow)
    : cells_(side, grid),
      kind_(kind),
      su_(1.0),
      sv_(1.0),
      gas_constant_(gas_constant),
      inflow_(std::move(inflow)) {
  if (kind == BoundaryKind::NoSlipWall) su_ = sv_ = -1.0;
  if (kind == BoundaryKind::SlipWall) (is_x_side(side) ? su_ : sv_) = -1.0;
}

void PhysicalBoundary::fill(const PrimitiveGhosts& ghosts) {
  const PrimitiveArrays f = arrays(ghosts);
  const SideCells& s = cells_;
  const int last_inflow = static_cast<int>(inflow_.size()) - 1;
#pragma omp for schedule(static) nowait
  for (int line = s.line_begin; line < s.line_end; ++line) {
    for (int g = 0; g < s.ghosts; ++g) {
      const std::size_t dst = s.cell(line, s.ghost(g));
      if (kind_ == BoundaryKind::Inflow) {
        const PrimitiveState& in =
            inflow_[static_cast<std::size_t>(std::clamp(line, 0, last_inflow))];
        f.rho[dst] = in.rho;
        f.u[dst] = in.u;
        f.v[dst] = in.v;
        f.p[dst] = in.p;
        f.T[dst] = temperature_of(in, gas_constant_);
        continue;
      }
      // An outflow copies the last interior cell; a wall mirrors the cells next to it.
      const int k = kind_ == BoundaryKind::Outflow ? 0 : mirror_cell(g, s.n);
      copy_state(f, dst, s.cell(line, from_end(s, k)), su_, sv_);
    }
  }
}

void PhysicalBoundary::fill_porosity(Field2D& alpha) {
  copy_layers(alpha, cells_, [this](int g) { return from_end(cells_, mirror_cell(g, cells_.n)); });
}

PeriodicBoundary::PeriodicBoundary(GridSide side, const Grid2D& grid) : cells_(side, grid) {}

int PeriodicBoundary::source(int g) const {
  const int n = cells_.n;
  return cells_.low ? ((n - 1 - g) % n + n) % n : g % n;
}

void PeriodicBoundary::fill(const PrimitiveGhosts& ghosts) {
  const PrimitiveArrays f = arrays(ghosts);
  const SideCells& s = cells_;
#pragma omp for schedule(static) nowait
  for (int line = s.line_begin; line < s.line_end; ++line) {
    for (int g = 0; g < s.ghosts; ++g) {
      copy_state(f, s.cell(line, s.ghost(g)), s.cell(line, source(g)), 1.0, 1.0);
    }
  }
}

void PeriodicBoundary::fill_porosity(Field2D& alpha) {
  copy_layers(alpha, cells_, [this](int g) { return source(g); });
}

std::unique_ptr<GhostFiller> make_boundary_filler(GridSide side, BoundaryKind kind,
                                                  const Grid2D& grid, double gas_constant,
                                                  std::vector<PrimitiveState> inflow) {
  if (kind == BoundaryKind::Periodic) return std::make_unique<PeriodicBoundary>(side, grid);
  return std::make_unique<PhysicalBoundary>(side, kind, grid, gas_constant, std::move(inflow));
}

}  // namespace dustlift
