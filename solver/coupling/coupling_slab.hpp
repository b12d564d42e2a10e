#pragma once
// The coupling on one MPI rank's x-slab of the grid (docs/parallel.md): everything the slab
// adds to the one-rank coupling in one place. The physics is one-rank code given an optional
// slab (null: one rank holds the whole grid); the slab says where its grid lies in the whole
// one, fills the ghost columns at its cuts and gives the collectives over the ranks.
#include <span>
#include <string>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {

class Communicator;
class GasHalo;

struct CouplingSlab {
  /// The whole grid: stencils are located on it (a slab would clamp them at its cut).
  const Grid2D* whole = nullptr;
  int first_column = 0;  ///< of the slab in the whole grid
  GasHalo* halo = nullptr;
  const Communicator* comm = nullptr;
  /// The implicit exchange factors per cell, exchanged at the cuts (a parcel at a cut reads
  /// the neighbour's too).
  Field2D drag_factor, heat_factor;
  std::vector<double> sample_x;  ///< parcel x for sampling (other ranks' copies kept inside)
  std::vector<Field2D*>
      derived_fields;  ///< the coupling's vorticity and grad p, exchanged at the cuts

  /// The largest value over the ranks (collective), as -min(-value): bitwise the largest.
  double max(double value) const;
  /// Element by element, in place (one message for all of them).
  void max_each(std::span<double> values) const;
  /// Collective: the lowest-numbered rank's non-empty text ("" when none), so that a failure
  /// one rank finds stops every rank with the same message.
  std::string first_failure(const std::string& local) const;
};

/// Zero-gradient ghost values of rows [j0, j1) at the domain's ends (left and/or right) and of
/// the ghost rows at its bottom and top, so that interpolation next to the boundary sees the
/// edge cell.
void copy_edge_to_ghosts(const Grid2D& g, Field2D& f, int j0, int j1, bool left = true,
                         bool right = true);

/// The ghost values of these fields: the domain's ends and ghost rows as copy_edge_to_ghosts,
/// then on a slab the ghost columns at the cuts from the neighbours (collective).
void fill_ghosts(const Grid2D& grid, CouplingSlab* slab, std::span<Field2D* const> fields, int j0,
                 int j1);

}  // namespace dustlift
