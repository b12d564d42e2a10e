// Gas velocity and vorticity near the dust layer (paper Fig. 13) as an area series.
#include <algorithm>
#include <memory>

#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/series_observer.hpp"
#include "insitu/series_table.hpp"
#include "insitu/view_fields.hpp"

namespace dustlift {
namespace {

class NearLayerObserver final : public SeriesObserver {
 public:
  explicit NearLayerObserver(NearLayerOptions options)
      : SeriesObserver("near_layer"),
        options_(options),
        table_("near_layer", {{"time", "s"},
                              {"x", "m"},
                              {"y", "m"},
                              {"u", "m/s"},
                              {"v", "m/s"},
                              {"vorticity", "1/s"},
                              {"alpha_p", "1"}}) {
    keep({&table_});
  }

  // u, v and alpha_p (the gas gathers whole).
  unsigned output_reads() const override { return kReadsGas | kReadsAlphaP; }
  void on_output(const StateView& view) override {
    if (sampled_at(view.time)) return;  // on_finish right after an output
    const Grid2D& g = *view.grid;
    const GasPrimitives& p = view.primitives;
    // Rows and columns whose centres lie in the window.
    int i0 = g.nx(), i1 = -1, j0 = g.ny(), j1 = -1;
    for (int i = 0; i < g.nx(); ++i) {
      const double x = g.x().center(i);
      if (x >= options_.x_min && x <= options_.x_max) i0 = std::min(i0, i), i1 = std::max(i1, i);
    }
    for (int j = 0; j < g.ny(); ++j) {
      const double y = g.y().center(j);
      if (y >= options_.y_min && y <= options_.y_max) j0 = std::min(j0, j), j1 = std::max(j1, j);
    }
    if (i1 < i0 || j1 < j0) return;
    const Field2D& vorticity = derived_field(view, "vorticity");
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const double ap =
            view.alpha_p != nullptr ? (*view.alpha_p)(i, j) : 1.0 - (*p.alpha_g)(i, j);
        const double row[] = {view.time,
                              g.x().center(i),
                              g.y().center(j),
                              (*p.u)(i, j),
                              (*p.v)(i, j),
                              vorticity(i, j),
                              ap};
        table_.append_row(row);
      }
    }
    write_series(view);
    mark_sampled(view.time);
  }

 private:
  NearLayerOptions options_;
  SeriesTable table_;
};

}  // namespace

std::unique_ptr<Observer> make_near_layer_observer(NearLayerOptions options) {
  return std::make_unique<NearLayerObserver>(options);
}

}  // namespace dustlift
