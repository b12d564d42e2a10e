#include "solver/coupling/coupling_slab.hpp"

#include <algorithm>

#include "solver/coupling/gas_halo.hpp"
#include "solver/core/communicator.hpp"

namespace dustlift {

double CouplingSlab::max(double value) const {
  return -comm->min(-value);
}

void CouplingSlab::max_each(std::span<double> values) const {
  for (double& v : values) v = -v;
  comm->min_each(values);
  for (double& v : values) v = -v;
}

std::string CouplingSlab::first_failure(const std::string& local) const {
  return comm->first_nonempty(local);
}

void copy_edge_to_ghosts(const Grid2D& g, Field2D& f, int j0, int j1, bool left, bool right) {
  // At the domain's own ends only: a slab's cut columns come from its neighbour.
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

void fill_ghosts(const Grid2D& grid, CouplingSlab* slab, std::span<Field2D* const> fields, int j0,
                 int j1) {
  const bool left = slab == nullptr || slab->halo->owns_left_boundary();
  const bool right = slab == nullptr || slab->halo->owns_right_boundary();
  for (Field2D* f : fields) copy_edge_to_ghosts(grid, *f, j0, j1, left, right);
  if (slab != nullptr) slab->halo->exchange_columns(fields);
}

}  // namespace dustlift
