// Observers that turn gas fields into ready-to-plot series (surface height, shock
// position). They read only the primitive fields: no GasSolver call, no VTK.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "insitu/observers.hpp"
#include "insitu/series_observer.hpp"
#include "insitu/series_table.hpp"
#include "insitu/shock_position.hpp"
#include "insitu/surface_height.hpp"
#include "insitu/view_fields.hpp"
#include "solver/core/derivatives.hpp"

namespace dustlift {
namespace {

void require_grid(const StateView& view, const Field2D* field, const char* who) {
  if (!view.grid || !field)
    throw std::invalid_argument(fmt::format("{}: the state view has no grid or field", who));
}

class SurfaceHeightObserver final : public SeriesObserver {
 public:
  explicit SurfaceHeightObserver(SurfaceHeightOptions options)
      : SeriesObserver("surface_height"),
        options_(std::move(options)),
        profile_("surface_height", {{"time", "s"}, {"x", "m"}, {"height", "m"}}),
        stations_("surface_height_stations", station_columns(options_.stations_x)) {
    keep({&profile_, &stations_});
  }

  unsigned output_reads() const override { return kReadsAlphaP; }
  void on_output(const StateView& view) override {
    require_grid(view, view.primitives.alpha_g, "SurfaceHeightObserver");
    if (sampled_at(view.time)) return;  // on_finish right after an output
    const Grid2D& grid = *view.grid;
    if (view.alpha_p != nullptr) {
      interior_values(grid, *view.alpha_p, alpha_p_);
    } else {
      interior_values(grid, *view.primitives.alpha_g, alpha_p_, [](double ag) { return 1.0 - ag; });
    }
    const auto xc = interior_centers(grid.x());
    const auto heights =
        dust_surface_height(grid.y().interior_faces(), alpha_p_,
                            static_cast<std::size_t>(grid.nx()), options_.threshold);
    for (std::size_t i = 0; i < heights.size(); ++i)
      if (!std::isnan(heights[i])) profile_.append_row(std::vector{view.time, xc[i], heights[i]});
    std::vector<double> row{view.time};
    for (double x : options_.stations_x) row.push_back(height_at_station(xc, heights, x));
    stations_.append_row(row);
    write_series(view);
    mark_sampled(view.time);
  }

 private:
  void write_tables(const SeriesSink& sink) override {
    sink.write(profile_);
    if (!options_.stations_x.empty()) sink.write(stations_);
  }
  static std::vector<SeriesColumn> station_columns(const std::vector<double>& xs) {
    std::vector<SeriesColumn> c{{"time", "s"}};
    for (double x : xs) c.push_back({"height_at_x" + number_in_identifier(x), "m"});
    return c;
  }
  SurfaceHeightOptions options_;
  SeriesTable profile_, stations_;
  std::vector<double> alpha_p_;
};

class ShockPositionObserver final : public SeriesObserver {
 public:
  explicit ShockPositionObserver(ShockPositionOptions options)
      : SeriesObserver("shock_position"),
        options_(options),
        table_("shock_position", {{"time", "s"}, {"x", "m"}}) {
    keep({&table_});
  }

  bool reads_step(const StateView&) const override { return options_.every_step; }
  unsigned step_reads() const override { return kReadsPressure; }
  unsigned output_reads() const override { return kReadsPressure; }
  void on_step(const StateView& view) override {
    if (options_.every_step) sample(view);
  }
  void on_output(const StateView& view) override {
    sample(view);
    write_series(view);
  }

 private:
  void sample(const StateView& view) {
    require_grid(view, view.primitives.p, "ShockPositionObserver");
    if (sampled_at(view.time)) return;
    const Grid2D& grid = *view.grid;
    if (x_centers_.empty()) {
      x_centers_ = interior_centers(grid.x());
      y_centers_ = interior_centers(grid.y());
    }
    const double x = shock_position(grid, *view.primitives.p, x_centers_, y_centers_,
                                    options_.p_ambient, options_.threshold, options_.y_min);
    table_.append_row(std::vector{view.time, x});
    mark_sampled(view.time);
  }
  ShockPositionOptions options_;
  SeriesTable table_;
  std::vector<double> x_centers_, y_centers_;
};

}  // namespace

std::unique_ptr<Observer> make_surface_height_observer(SurfaceHeightOptions options) {
  return std::make_unique<SurfaceHeightObserver>(std::move(options));
}

std::unique_ptr<Observer> make_shock_position_observer(ShockPositionOptions options) {
  return std::make_unique<ShockPositionObserver>(options);
}

}  // namespace dustlift
