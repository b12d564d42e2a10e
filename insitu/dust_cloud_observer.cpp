// Series dust_cloud: the lifted cloud at each output (dust_cloud.hpp), with the shock's
// position for the distances behind it, and per size class when the layer holds several.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "insitu/dust_cloud.hpp"
#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/series_state.hpp"
#include "insitu/series_table.hpp"
#include "insitu/shock_position.hpp"
#include "insitu/view_fields.hpp"
#include "solver/core/derivatives.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {
namespace {

/// The columns of one class's lifted dust, named with `prefix` ("" for the whole cloud).
std::vector<SeriesColumn> lifted_columns(const std::string& prefix) {
  return {{prefix + "lifted_mass", "kg/m"},
          {prefix + "lifted_share", "1"},
          {prefix + "height_p50", "m"},
          {prefix + "height_p90", "m"},
          {prefix + "height_p99", "m"},
          {prefix + "lifted_temperature_max", "K"},
          {prefix + "lifted_temperature_mean", "K"}};
}

std::vector<SeriesColumn> cloud_columns(int classes) {
  std::vector<SeriesColumn> c{{"time", "s"}};
  for (const SeriesColumn& l : lifted_columns("")) c.push_back(l);
  for (const SeriesColumn& l : std::vector<SeriesColumn>{{"resting_mass", "kg/m"},
                                                         {"layer_mass", "kg/m"},
                                                         {"cloud_top", "m"},
                                                         {"explosible_area", "m^2"},
                                                         {"explosible_x_min", "m"},
                                                         {"explosible_x_max", "m"},
                                                         {"shock_x", "m"},
                                                         {"first_lifted_behind_shock", "m"},
                                                         {"densest_lifted_behind_shock", "m"}})
    c.push_back(l);
  if (classes > 1)
    for (int k = 0; k < classes; ++k)
      for (const SeriesColumn& l : lifted_columns(fmt::format("class{}_", k))) c.push_back(l);
  return c;
}

void append_lifted(std::vector<double>& row, const LiftedDust& d, double layer_mass) {
  row.insert(row.end(), {d.lifted_mass, d.lifted_mass / layer_mass, d.height_p50, d.height_p90,
                         d.height_p99, d.temperature_max, d.temperature_mean});
}

class DustCloudObserver final : public Observer {
 public:
  DustCloudObserver(DustCloudOptions options, ShockPositionOptions shock, bool shock_along_x)
      : options_(options),
        shock_(shock),
        shock_along_x_(shock_along_x),
        table_("dust_cloud", cloud_columns(options.classes)),
        layer_("dust_cloud_layer", layer_columns(options.classes)) {}

  unsigned output_reads() const override { return kReadsParcels | kReadsAlphaP | kReadsPressure; }
  void on_output(const StateView& view) override {
    if (view.parcels == nullptr || view.grid == nullptr) return;
    if (sampled_ && view.time == last_time_) return;  // on_finish right after an output
    const ParcelSystem& p = *view.parcels;
    const Grid2D& grid = *view.grid;
    if (layer_.rows() == 0) layer_.append_row(class_masses(p));  // the layer as it starts
    const Field2D& c = dust_concentration_of(view, concentration_scratch_);
    interior_values(grid, c, concentration_);
    interior_values(grid, *view.primitives.p, pressure_);
    const std::vector<double> x_faces = grid.x().interior_faces(),
                              y_faces = grid.y().interior_faces();
    const DustCloud cloud = dust_cloud({p.x, p.y, p.mass, p.temperature, p.size_class},
                                       {x_faces, y_faces, concentration_}, options_, column_mass_);
    double shock_x = std::numeric_limits<double>::quiet_NaN();
    if (shock_along_x_)
      shock_x = shock_position(interior_centers(grid.x()), interior_centers(grid.y()), pressure_,
                               shock_.p_ambient, shock_.threshold, shock_.y_min);

    const double layer_mass = layer_.column(layer_.columns().size() - 1).front();
    std::vector<double> row{view.time};
    append_lifted(row, cloud.all, layer_mass);
    row.insert(row.end(),
               {cloud.all.resting_mass, layer_mass, cloud.cloud_top, cloud.explosible_area,
                cloud.explosible_x_min, cloud.explosible_x_max, shock_x,
                shock_x - cloud.first_lifted_x, shock_x - cloud.densest_lifted_x});
    if (options_.classes > 1)
      for (int k = 0; k < options_.classes; ++k)
        append_lifted(row, cloud.per_class[static_cast<std::size_t>(k)],
                      layer_.column(static_cast<std::size_t>(k)).front());
    table_.append_row(row);
    sampled_ = true;
    last_time_ = view.time;
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
  }

  std::string state_key() const override { return "dust_cloud"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    save_series_state({&table_, &layer_}, last_time_, sampled_, s, prefix);
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    sampled_ = restore_series_state({&table_, &layer_}, last_time_, s, prefix);
  }
  void on_resume(const StateView& view, const std::string&) override {
    if (!sampled_) return;
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
  }

 private:
  /// The layer's mass per class, then in all (kg/m): what the lifted shares divide by.
  static std::vector<SeriesColumn> layer_columns(int classes) {
    std::vector<SeriesColumn> c;
    for (int k = 0; k < classes; ++k) c.push_back({fmt::format("class{}_mass", k), "kg/m"});
    c.push_back({"mass", "kg/m"});
    return c;
  }
  std::vector<double> class_masses(const ParcelSystem& p) const {
    std::vector<double> m(static_cast<std::size_t>(options_.classes) + 1, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double k = p.size_class[i];
      if (!(k >= 0.0 && k < options_.classes))
        throw std::invalid_argument(fmt::format(
            "dust_cloud: parcel size class {} is not one of the {} classes", k, options_.classes));
      m[static_cast<std::size_t>(k)] += p.mass[i];
      m.back() += p.mass[i];
    }
    return m;
  }

  DustCloudOptions options_;
  ShockPositionOptions shock_;
  bool shock_along_x_;
  SeriesTable table_, layer_;
  std::unique_ptr<SeriesSink> sink_;
  Field2D concentration_scratch_;
  std::vector<double> concentration_, pressure_, column_mass_;
  bool sampled_ = false;
  double last_time_ = 0.0;
};

}  // namespace

std::unique_ptr<Observer> make_dust_cloud_observer(DustCloudOptions options,
                                                   ShockPositionOptions shock, bool shock_along_x) {
  return std::make_unique<DustCloudObserver>(options, shock, shock_along_x);
}

}  // namespace dustlift
