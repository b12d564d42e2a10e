// Series dust_cloud: the lifted cloud at each output (dust_cloud.hpp), with the shock's
// position for the distances behind it, its filtered concentration's explosible band, the
// entrainment rate and fluxes (entrainment.hpp), and per size class when the layer holds
// several. Series dust_concentration_histogram: the lifted mass per filtered-concentration
// bin. Series dust_entrainment: per stretch of channel, the entrainment rate, the fluxes
// through the heights and the cloud's height, against the distance behind the shock.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "insitu/dust_cloud.hpp"
#include "insitu/entrainment.hpp"
#include "insitu/observers.hpp"
#include "insitu/series_observer.hpp"
#include "insitu/series_table.hpp"
#include "insitu/shock_position.hpp"
#include "insitu/view_fields.hpp"
#include "solver/core/derivatives.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

std::string height_name(double h) {
  return fmt::format("h{}", number_in_identifier(h));
}

std::vector<SeriesColumn> cloud_columns(int classes, const std::vector<double>& heights) {
  std::vector<SeriesColumn> c{{"time", "s"}};
  for (const SeriesColumn& l : lifted_columns("")) c.push_back(l);
  for (const SeriesColumn& l :
       std::vector<SeriesColumn>{{"resting_mass", "kg/m"},
                                 {"layer_mass", "kg/m"},
                                 {"cloud_top", "m"},
                                 {"explosible_area", "m^2"},
                                 {"explosible_x_min", "m"},
                                 {"explosible_x_max", "m"},
                                 {"shock_x", "m"},
                                 {"first_lifted_behind_shock", "m"},
                                 {"densest_lifted_behind_shock", "m"},
                                 {"explosible_mass", "kg/m"},
                                 {"explosible_mean_concentration", "kg/m^3"},
                                 {"cloud_area", "m^2"},
                                 {"cloud_mean_concentration", "kg/m^3"},
                                 {"fines_lifted_mass", "kg/m"},
                                 {"fines_cloud_mean_concentration", "kg/m^3"},
                                 {"fines_explosible_mass", "kg/m"},
                                 {"fines_explosible_mean_concentration", "kg/m^3"},
                                 {"filter_width", "m"},
                                 {"concentration_quantum", "kg/m^3"},
                                 {"entrainment_rate", "kg/(m s)"}})
    c.push_back(l);
  for (double h : heights) c.push_back({"mass_above_" + height_name(h), "kg/m"});
  for (double h : heights) c.push_back({"flux_at_" + height_name(h), "kg/(m s)"});
  if (classes > 1)
    for (int k = 0; k < classes; ++k)
      for (const SeriesColumn& l : lifted_columns(fmt::format("class{}_", k))) c.push_back(l);
  return c;
}

std::vector<SeriesColumn> histogram_columns() {
  return {{"time", "s"},
          {"concentration", "kg/m^3"},
          {"concentration_low", "kg/m^3"},
          {"concentration_high", "kg/m^3"},
          {"mass", "kg/m"},
          {"fines_mass", "kg/m"},
          {"area", "m^2"}};
}

std::vector<SeriesColumn> entrainment_columns(const std::vector<double>& heights) {
  std::vector<SeriesColumn> c{{"time", "s"},
                              {"x", "m"},
                              {"distance_behind_shock", "m"},
                              {"entrainment_rate", "kg/(m^2 s)"}};
  for (double h : heights) c.push_back({"flux_at_" + height_name(h), "kg/(m^2 s)"});
  c.push_back({"height_p90", "m"});
  c.push_back({"height_max", "m"});
  return c;
}

void append_lifted(std::vector<double>& row, const LiftedDust& d, double layer_mass) {
  row.insert(row.end(), {d.lifted_mass, d.lifted_mass / layer_mass, d.height_p50, d.height_p90,
                         d.height_p99, d.temperature_max, d.temperature_mean});
}

class DustCloudObserver final : public SeriesObserver {
 public:
  DustCloudObserver(DustCloudOptions options, EntrainmentOptions entrainment,
                    ShockPositionOptions shock, bool shock_along_x)
      : SeriesObserver("dust_cloud"),
        options_(std::move(options)),
        shock_(shock),
        shock_along_x_(shock_along_x),
        entrainment_(entrainment),
        table_("dust_cloud", cloud_columns(options_.classes, options_.heights)),
        layer_("dust_cloud_layer", layer_columns(options_.classes)),
        histogram_("dust_concentration_histogram", histogram_columns()),
        rates_("dust_entrainment", entrainment_columns(options_.heights)) {
    keep({&table_, &layer_, &histogram_, &rates_});
  }

  unsigned output_reads() const override { return kReadsParcels | kReadsAlphaP | kReadsPressure; }
  void on_output(const StateView& view) override {
    if (view.parcels == nullptr || view.grid == nullptr) return;
    if (sampled_at(view.time)) return;  // on_finish right after an output
    const ParcelSystem& p = *view.parcels;
    const Grid2D& grid = *view.grid;
    if (layer_.rows() == 0) layer_.append_row(class_masses(p));  // the layer as it starts
    const Field2D& c = derived_field(view, "dust_concentration");
    interior_values(grid, c, concentration_);
    interior_values(grid, *view.primitives.p, pressure_);
    const std::vector<double> x_faces = grid.x().interior_faces(),
                              y_faces = grid.y().interior_faces();
    const DustCloud cloud =
        dust_cloud({p.x, p.y, p.mass, p.temperature, p.size_class, p.real_diameter},
                   {x_faces, y_faces, concentration_}, options_, scratch_);
    const EntrainmentSample rates =
        entrainment_.sample({p.id, p.x, p.y, p.x_initial, p.mass}, view.time);
    double shock_x = kNaN;
    if (shock_along_x_)
      shock_x = shock_position(interior_centers(grid.x()), interior_centers(grid.y()), pressure_,
                               shock_.p_ambient, shock_.threshold, shock_.y_min);
    warn_once(view, cloud.filtered.quantum);

    const double layer_mass = layer_.column(layer_.columns().size() - 1).front();
    const FilteredCloud& f = cloud.filtered;
    std::vector<double> row{view.time};
    append_lifted(row, cloud.all, layer_mass);
    row.insert(row.end(), {cloud.all.resting_mass,
                           layer_mass,
                           cloud.cloud_top,
                           f.explosible_area,
                           f.explosible_x_min,
                           f.explosible_x_max,
                           shock_x,
                           shock_x - cloud.first_lifted_x,
                           shock_x - cloud.densest_lifted_x,
                           f.explosible_mass,
                           f.explosible_concentration,
                           f.cloud_area,
                           f.cloud_concentration,
                           f.fines_lifted_mass,
                           f.fines_cloud_concentration,
                           f.fines_explosible_mass,
                           f.fines_explosible_concentration,
                           options_.filter_width,
                           f.quantum,
                           rates.lifted_rate});
    row.insert(row.end(), cloud.mass_above.begin(), cloud.mass_above.end());
    row.insert(row.end(), rates.height_rate.begin(), rates.height_rate.end());
    if (options_.classes > 1)
      for (int k = 0; k < options_.classes; ++k)
        append_lifted(row, cloud.per_class[static_cast<std::size_t>(k)],
                      layer_.column(static_cast<std::size_t>(k)).front());
    // The rates are over the interval since the last output: the shock midway through it.
    const double shock_mid =
        table_.rows() > 0 ? 0.5 * (table_.column(shock_column()).back() + shock_x) : kNaN;
    table_.append_row(row);
    append_histogram(view.time, f);
    if (rates.has_rates) append_rates(view.time, shock_mid, rates);
    mark_sampled(view.time);
    write_series(view);
  }

  void on_resume(const StateView& view, const std::string& previous_output_dir) override {
    if (sampled() && view.parcels != nullptr) {
      double largest = 0.0;
      for (double m : view.parcels->mass) largest = std::max(largest, m);
      warn_once(view, concentration_quantum(largest, options_.filter_width));
    }
    SeriesObserver::on_resume(view, previous_output_dir);
  }

 private:
  void save_more(Snapshot& s, const std::string& prefix) const override {
    entrainment_.save(s, prefix);
  }
  void restore_more(const Snapshot& s, const std::string& prefix) override {
    entrainment_.restore(s, prefix);
  }
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
  std::size_t shock_column() const {
    const auto& c = table_.columns();
    return static_cast<std::size_t>(
        std::find_if(c.begin(), c.end(),
                     [](const SeriesColumn& k) { return k.name == "shock_x"; }) -
        c.begin());
  }
  void append_histogram(double time, const FilteredCloud& f) {
    for (int k = 0; k < kHistogramBins; ++k) {
      const auto b = static_cast<std::size_t>(k);
      const double lo = histogram_edge(k), hi = histogram_edge(k + 1);
      histogram_.append_row(std::vector<double>{time, std::sqrt(lo * hi), lo, hi,
                                                f.histogram_mass[b], f.histogram_fines[b],
                                                f.histogram_area[b]});
    }
  }
  void append_rates(double time, double shock_mid, const EntrainmentSample& r) {
    std::vector<double> row;
    for (std::size_t b = 0; b < r.bin_x.size(); ++b) {
      row = {time, r.bin_x[b], shock_mid - r.bin_x[b], r.entrainment[b]};
      for (const auto& flux : r.height_flux) row.push_back(flux[b]);
      row.insert(row.end(), {r.height_p90[b], r.height_max[b]});
      rates_.append_row(row);
    }
  }
  // The layer's masses stay in the checkpoint only: every lifted share divides by them.
  void write_tables(const SeriesSink& sink) override {
    sink.write(table_);
    sink.write(histogram_);
    if (rates_.rows() > 0) sink.write(rates_);
  }
  void warn_once(const StateView& view, double quantum) {
    if (warned_) return;
    warned_ = true;
    const std::string text = quantum_warning(quantum, options_);
    if (!text.empty() && view.log != nullptr) (*view.log)(text);
  }

  DustCloudOptions options_;
  ShockPositionOptions shock_;
  bool shock_along_x_;
  Entrainment entrainment_;
  SeriesTable table_, layer_, histogram_, rates_;
  std::vector<double> concentration_, pressure_;
  DustCloudScratch scratch_;
  bool warned_ = false;
};

}  // namespace

std::unique_ptr<Observer> make_dust_cloud_observer(DustCloudOptions options,
                                                   EntrainmentOptions entrainment,
                                                   ShockPositionOptions shock, bool shock_along_x) {
  return std::make_unique<DustCloudObserver>(std::move(options), std::move(entrainment), shock,
                                             shock_along_x);
}

}  // namespace dustlift
