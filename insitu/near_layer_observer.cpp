// Gas velocity and vorticity near the dust layer (paper Fig. 13) as an area series.
#include <algorithm>
#include <memory>

#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/series_state.hpp"
#include "insitu/series_table.hpp"
#include "insitu/view_fields.hpp"

namespace dustlift {
namespace {

class NearLayerObserver final : public Observer {
 public:
  explicit NearLayerObserver(NearLayerOptions options)
      : options_(options),
        table_("near_layer", {{"time", "s"},
                              {"x", "m"},
                              {"y", "m"},
                              {"u", "m/s"},
                              {"v", "m/s"},
                              {"vorticity", "1/s"},
                              {"alpha_p", "1"}}) {}

  // u, v and alpha_p (the gas gathers whole).
  unsigned output_reads() const override { return kReadsGas | kReadsAlphaP; }
  void on_output(const StateView& view) override {
    if (written_ && view.time == last_time_) return;  // on_finish right after an output
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
    const Field2D& vorticity = vorticity_of(view, vorticity_);
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
    write(view);
    written_ = true;
    last_time_ = view.time;
  }

  std::string state_key() const override { return "near_layer"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    save_series_state({&table_}, last_time_, written_, s, prefix);
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    written_ = restore_series_state({&table_}, last_time_, s, prefix);
  }
  void on_resume(const StateView& view, const std::string&) override {
    if (written_) write(view);
  }

 private:
  void write(const StateView& view) {
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
  }
  NearLayerOptions options_;
  SeriesTable table_;
  Field2D vorticity_;
  std::unique_ptr<SeriesSink> sink_;
  bool written_ = false;
  double last_time_ = 0.0;
};

}  // namespace

std::unique_ptr<Observer> make_near_layer_observer(NearLayerOptions options) {
  return std::make_unique<NearLayerObserver>(options);
}

}  // namespace dustlift
