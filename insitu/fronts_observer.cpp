// The streamwise fronts of the parcels as a series (a particle curtain's spreading, Ling et
// al. 2012 Fig. 14): parcel_fronts.csv with time_s, x_min_m, x_p01_m, x_p99_m, x_max_m.
#include <memory>

#include "insitu/observers.hpp"
#include "insitu/parcel_fronts.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/series_state.hpp"
#include "insitu/series_table.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {
namespace {

class FrontsObserver final : public Observer {
 public:
  FrontsObserver()
      : table_("parcel_fronts",
               {{"time", "s"}, {"x_min", "m"}, {"x_p01", "m"}, {"x_p99", "m"}, {"x_max", "m"}}) {}

  unsigned output_reads() const override { return kReadsParcels; }
  void on_output(const StateView& view) override {
    if (view.parcels == nullptr || view.parcels->size() == 0) return;
    if (sampled_ && view.time == last_time_) return;  // on_finish right after an output
    const ParcelSystem& p = *view.parcels;
    const ParcelFronts f = parcel_fronts(p.x, p.n_real, 0.01, order_);
    table_.append_row(std::vector{view.time, f.x_min, f.x_low, f.x_high, f.x_max});
    sampled_ = true;
    last_time_ = view.time;
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
  }

  std::string state_key() const override { return "parcel_fronts"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    save_series_state({&table_}, last_time_, sampled_, s, prefix);
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    sampled_ = restore_series_state({&table_}, last_time_, s, prefix);
  }
  void on_resume(const StateView& view, const std::string&) override {
    if (!sampled_) return;
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    sink_->write(table_);
  }

 private:
  SeriesTable table_;
  std::unique_ptr<SeriesSink> sink_;
  std::vector<std::size_t> order_;
  bool sampled_ = false;
  double last_time_ = 0.0;
};

}  // namespace

std::unique_ptr<Observer> make_parcel_fronts_observer() {
  return std::make_unique<FrontsObserver>();
}

}  // namespace dustlift
