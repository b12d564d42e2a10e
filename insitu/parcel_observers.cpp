// Observers over parcel arrays: the .vtp writer and the band-averaged force series.
// The parcel system is reached through adaptor functions (StateView -> array views), so
// these compile and are tested without the DEM module.
#include <fmt/core.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/series_observer.hpp"
#include "insitu/shock_position.hpp"
#include "insitu/vtk_files_observer.hpp"
#include "solver/core/communicator.hpp"
#include "solver/core/derivatives.hpp"

namespace dustlift {
namespace {

class VtkParcelWriter final : public VtkFilesObserver {
 public:
  explicit VtkParcelWriter(ParcelArraysOf parcels_of)
      : VtkFilesObserver("parcels_vtk", "parcels", "vtp"), parcels_of_(std::move(parcels_of)) {
    if (!parcels_of_) throw std::invalid_argument("VtkParcelWriter: no parcel adaptor");
  }

  void on_output(const StateView& view) override {
    VtkSeriesFiles& out = files(view);
    if (out.last_time_is(view.time)) return;  // on_finish right after that output
    if (view.piece == nullptr) {
      write_parcels_vtp(parcels_of_(view), out.next_path(view.time), vtk_file_info_of(view));
      out.commit(view.time);
      return;
    }
    // The rank's table holds copies of its neighbours' parcels: those are theirs to write.
    const ParcelArraysView all = parcels_of_(view);
    const ParcelArraysView own = kept_rows(all, view.piece->parcel_copies, own_);
    write_in_pieces(
        out, *view.piece, view.time, "vtp",
        [&](const std::string& path) { write_parcels_vtp(own, path, vtk_file_info_of(view)); },
        // The arrays every piece holds, from this rank's table (present even with no parcel of
        // its own).
        [&](const std::string& path, const std::vector<std::string>& sources) {
          write_parcels_pvtp(all, sources, path);
        });
  }

 private:
  ParcelArraysOf parcels_of_;
  ParcelArraysCopy own_;  // reused: no reallocation once sized
};

class BandForceObserver final : public SeriesObserver {
 public:
  BandForceObserver(BandForceOptions options, BandParcelsOf parcels_of)
      : SeriesObserver("bands", "last_sample_time"),
        options_(std::move(options)),
        parcels_of_(std::move(parcels_of)),
        series_(options_.bands, options_.averaging) {
    if (!parcels_of_) throw std::invalid_argument("BandForceObserver: no parcel adaptor");
    if (options_.bands.empty()) throw std::invalid_argument("BandForceObserver: no band");
  }
  bool reads_step(const StateView&) const override { return options_.sample_every_step; }
  // The band parcels, and the pressure for the shock's arrival.
  unsigned step_reads() const override { return kReadsPressure | kReadsBandParcels; }
  unsigned output_reads() const override { return step_reads(); }
  void on_step(const StateView& view) override {
    if (options_.sample_every_step) sample(view);
  }
  void on_output(const StateView& view) override {
    sample(view);
    write_series(view);
  }
  void on_finish(const StateView& view) override {
    on_output(view);
    if (trajectory_.ignored_jumps() > 0) {
      fmt::print(
          stderr,
          "band filter: {} shock positions ignored, each more than {:g} cells beyond the farthest "
          "one (pressure pulses ahead of the shock, docs/output.md)\n",
          trajectory_.ignored_jumps(), kMaxShockAdvanceCells);
    }
  }

  void on_resume(const StateView& view, const std::string&) override { write_series(view); }

 private:
  void save_more(Snapshot& s, const std::string& prefix) const override {
    s.f64[prefix + "shock_times"] = trajectory_.times();
    s.f64[prefix + "shock_reaches"] = trajectory_.reaches();
    series_.save_state(s, prefix);
  }
  void restore_more(const Snapshot& s, const std::string& prefix) override {
    try {
      trajectory_.assign(snapshot_array(s.f64, prefix + "shock_times"),
                         snapshot_array(s.f64, prefix + "shock_reaches"));
    } catch (const std::invalid_argument& e) {
      throw SnapshotError(prefix + "shock_times/shock_reaches: " + e.what());
    }
    series_.restore_state(s, prefix);
  }
  // The band tables are recomputed whole from the accumulators at each write.
  void write_tables(const SeriesSink& sink) override { series_.write(sink); }
  void sample(const StateView& view) {
    if (sampled_at(view.time)) return;
    if (!view.grid || !view.primitives.p)
      throw std::invalid_argument("BandForceObserver: the state view has no pressure field");
    const Grid2D& grid = *view.grid;
    if (x_centers_.empty()) {
      x_centers_ = interior_centers(grid.x());
      y_centers_ = interior_centers(grid.y());
    }
    const double shock_x =
        shock_position(grid, *view.primitives.p, x_centers_, y_centers_, options_.shock.p_ambient,
                       options_.shock.threshold, options_.shock.y_min);
    BandParcelsView parcels = parcels_of_(view);
    trajectory_.record(view.time, shock_x, max_shock_advance(grid.x()));
    arrival_.resize(parcels.count);
    band_arrival_times(trajectory_, options_.bands, parcels.initial_position.x,
                       parcels.initial_position.y, arrival_);
    parcels.arrival_time = arrival_;
    series_.add(parcels, view.time);
    mark_sampled(view.time);
  }
  /// How far beyond its reach a sampled shock may stand: kMaxShockAdvanceCells widths of the
  /// cell holding the reach when sampled every step (the shock moves less than one per step),
  /// no limit when sampled at outputs only.
  double max_shock_advance(const Axis& x) const {
    const double reach = trajectory_.reach();
    if (!options_.sample_every_step || std::isnan(reach))
      return std::numeric_limits<double>::infinity();
    return kMaxShockAdvanceCells * x.width(x.locate(reach));
  }
  static constexpr double kMaxShockAdvanceCells = 8.0;

  BandForceOptions options_;
  BandParcelsOf parcels_of_;
  BandForceSeries series_;
  ShockTrajectory trajectory_;
  std::vector<double> arrival_, x_centers_, y_centers_;
};

}  // namespace

std::unique_ptr<Observer> make_vtk_parcel_writer(ParcelArraysOf parcels_of) {
  return std::make_unique<VtkParcelWriter>(std::move(parcels_of));
}

std::unique_ptr<Observer> make_band_force_observer(BandForceOptions options,
                                                   BandParcelsOf parcels_of) {
  return std::make_unique<BandForceObserver>(std::move(options), std::move(parcels_of));
}

}  // namespace dustlift
