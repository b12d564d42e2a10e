// The streamwise fronts of the parcels as series (a particle curtain's spreading, Ling et al.
// 2012 Fig. 14): parcel_fronts.csv with time_s, the outermost parcels x_min_m and x_max_m, the
// 1 % and 99 % points x_p01_m and x_p99_m, and the edges a line of sight through the channel
// sees, x_sight_up_m and x_sight_down_m (parcel_fronts.hpp); line_of_sight.csv, the optical depth
// of every non-empty bin (an ensemble of runs averages it); and parcel_force_totals.csv, the x
// force of each part summed over every real particle (N per metre of depth), which says what
// moves the cloud.
#include <memory>
#include <utility>

#include "insitu/observers.hpp"
#include "insitu/parcel_fronts.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/series_state.hpp"
#include "insitu/series_table.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/scene/scene.hpp"

namespace dustlift {
namespace {

/// The force parts a scene's effects compute, with their series column names.
std::vector<std::pair<ForcePart, std::string>> parts_of(const Scene& scene) {
  const CouplingConfig& c = scene.coupling;
  std::vector<std::pair<ForcePart, std::string>> parts{{ForcePart::Contact, "contact_x"}};
  if (c.drag) parts.emplace_back(ForcePart::Drag, "drag_x");
  if (c.magnus) parts.emplace_back(ForcePart::Magnus, "magnus_x");
  if (c.pressure_force) parts.emplace_back(ForcePart::Pressure, "pressure_x");
  if (c.added_mass) parts.emplace_back(ForcePart::AddedMass, "added_mass_x");
  return parts;
}

SeriesTable totals_table(const std::vector<std::pair<ForcePart, std::string>>& parts) {
  std::vector<SeriesColumn> columns{{"time", "s"}};
  for (const auto& [part, name] : parts) columns.push_back({name, "N/m"});
  return SeriesTable("parcel_force_totals", std::move(columns));
}

class FrontsObserver final : public Observer {
 public:
  FrontsObserver(const LineOfSight& sight, std::vector<std::pair<ForcePart, std::string>> parts)
      : sight_(sight),
        parts_(std::move(parts)),
        table_("parcel_fronts", {{"time", "s"},
                                 {"x_min", "m"},
                                 {"x_p01", "m"},
                                 {"x_p99", "m"},
                                 {"x_max", "m"},
                                 {"x_sight_up", "m"},
                                 {"x_sight_down", "m"}}),
        totals_(totals_table(parts_)),
        profile_table_("line_of_sight", {{"time", "s"}, {"x", "m"}, {"optical_depth", "1"}}) {}

  unsigned output_reads() const override { return kReadsParcels; }
  void on_output(const StateView& view) override {
    if (view.parcels == nullptr || view.parcels->size() == 0) return;
    if (sampled_ && view.time == last_time_) return;  // on_finish right after an output
    const ParcelSystem& p = *view.parcels;
    const ParcelFronts f = parcel_fronts(p.x, p.n_real, 0.01, order_);
    const SightEdges e = line_of_sight_edges(p.x, p.n_real, p.real_diameter, sight_, profile_);
    for (std::size_t b = 0; b < profile_.tau.size(); ++b) {
      if (profile_.tau[b] <= 0.0) continue;
      const double centre = (profile_.first + static_cast<double>(b) + 0.5) * sight_.bin;
      profile_table_.append_row(std::vector{view.time, centre, profile_.tau[b]});
    }
    table_.append_row(
        std::vector{view.time, f.x_min, f.x_low, f.x_high, f.x_max, e.upstream, e.downstream});
    std::vector<double> row{view.time};
    for (const auto& [part, name] : parts_) {
      const std::vector<double>* fx = part == ForcePart::Contact ? &p.contact_fx : nullptr;
      if (fx == nullptr && p.find_part(part, 0).valid()) fx = &p.column(p.find_part(part, 0));
      double sum = 0.0;
      if (fx != nullptr)
        for (std::size_t k = 0; k < p.size(); ++k) sum += p.n_real[k] * (*fx)[k];
      row.push_back(sum);
    }
    totals_.append_row(row);
    sampled_ = true;
    last_time_ = view.time;
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
    sink_->write(totals_);
    sink_->write(profile_table_);
  }

  std::string state_key() const override { return "parcel_fronts"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    save_series_state({&table_, &totals_, &profile_table_}, last_time_, sampled_, s, prefix);
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    sampled_ = restore_series_state({&table_, &totals_, &profile_table_}, last_time_, s, prefix);
  }
  void on_resume(const StateView& view, const std::string&) override {
    if (!sampled_) return;
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
    sink_->write(totals_);
    sink_->write(profile_table_);
  }

 private:
  LineOfSight sight_;
  std::vector<std::pair<ForcePart, std::string>> parts_;
  SeriesTable table_, totals_, profile_table_;
  std::unique_ptr<SeriesSink> sink_;
  std::vector<std::size_t> order_;
  SightProfile profile_;
  bool sampled_ = false;
  double last_time_ = 0.0;
};

}  // namespace

std::unique_ptr<Observer> make_parcel_fronts_observer(const Scene& scene) {
  const auto& l = scene.output.line_of_sight;
  const LineOfSight sight{l.depth, l.optical_depth, l.bin, scene.grid.y.end - scene.grid.y.start};
  return std::make_unique<FrontsObserver>(sight, parts_of(scene));
}

}  // namespace dustlift
