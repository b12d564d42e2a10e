// Observers that turn gas fields into ready-to-plot series (surface height, shock
// position). They read only the primitive fields: no GasSolver call, no VTK.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/series_state.hpp"
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

class SurfaceHeightObserver final : public Observer {
 public:
  explicit SurfaceHeightObserver(SurfaceHeightOptions options)
      : options_(std::move(options)),
        profile_("surface_height", {{"time", "s"}, {"x", "m"}, {"height", "m"}}),
        stations_("surface_height_stations", station_columns(options_.stations_x)) {}

  unsigned output_reads() const override { return kReadsAlphaP; }
  void on_output(const StateView& view) override {
    require_grid(view, view.primitives.alpha_g, "SurfaceHeightObserver");
    if (written_ && view.time == last_time_) return;  // on_finish right after an output
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
    write(view);
    written_ = true;
    last_time_ = view.time;
  }

  std::string state_key() const override { return "surface_height"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    save_series_state({&profile_, &stations_}, last_time_, written_, s, prefix);
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    written_ = restore_series_state({&profile_, &stations_}, last_time_, s, prefix);
  }
  void on_resume(const StateView& view, const std::string&) override {
    if (written_) write(view);
  }

 private:
  void write(const StateView& view) {
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(profile_);
    if (!options_.stations_x.empty()) sink_->write(stations_);
  }
  static std::vector<SeriesColumn> station_columns(const std::vector<double>& xs) {
    std::vector<SeriesColumn> c{{"time", "s"}};
    for (double x : xs) c.push_back({"height_at_x" + number_in_identifier(x), "m"});
    return c;
  }
  SurfaceHeightOptions options_;
  SeriesTable profile_, stations_;
  std::unique_ptr<SeriesSink> sink_;
  std::vector<double> alpha_p_;
  bool written_ = false;
  double last_time_ = 0.0;
};

class ShockPositionObserver final : public Observer {
 public:
  explicit ShockPositionObserver(ShockPositionOptions options)
      : options_(options), table_("shock_position", {{"time", "s"}, {"x", "m"}}) {}

  bool reads_step(const StateView&) const override { return options_.every_step; }
  unsigned step_reads() const override { return kReadsPressure; }
  unsigned output_reads() const override { return kReadsPressure; }
  void on_step(const StateView& view) override {
    if (options_.every_step) sample(view);
  }
  void on_output(const StateView& view) override {
    sample(view);
    write(view);
  }

  std::string state_key() const override { return "shock_position"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    save_series_state({&table_}, last_time_, sampled_, s, prefix);
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    sampled_ = restore_series_state({&table_}, last_time_, s, prefix);
  }
  void on_resume(const StateView& view, const std::string&) override {
    if (sampled_) write(view);
  }

 private:
  void write(const StateView& view) {
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
  }
  void sample(const StateView& view) {
    require_grid(view, view.primitives.p, "ShockPositionObserver");
    if (sampled_ && view.time == last_time_) return;
    const Grid2D& grid = *view.grid;
    interior_values(grid, *view.primitives.p, pressure_);
    if (x_centers_.empty()) {
      x_centers_ = interior_centers(grid.x());
      y_centers_ = interior_centers(grid.y());
    }
    const double x = shock_position(x_centers_, y_centers_, pressure_, options_.p_ambient,
                                    options_.threshold, options_.y_min);
    table_.append_row(std::vector{view.time, x});
    sampled_ = true;
    last_time_ = view.time;
  }
  ShockPositionOptions options_;
  SeriesTable table_;
  std::unique_ptr<SeriesSink> sink_;
  std::vector<double> pressure_, x_centers_, y_centers_;
  bool sampled_ = false;
  double last_time_ = 0.0;
};

}  // namespace

std::unique_ptr<Observer> make_surface_height_observer(SurfaceHeightOptions options) {
  return std::make_unique<SurfaceHeightObserver>(std::move(options));
}

std::unique_ptr<Observer> make_shock_position_observer(ShockPositionOptions options) {
  return std::make_unique<ShockPositionObserver>(options);
}

}  // namespace dustlift
