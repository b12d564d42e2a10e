// Observers over parcel arrays: the .vtp writer and the band-averaged force series.
// The parcel system is reached through adaptor functions (StateView -> array views), so
// these compile and are tested without the DEM module.
#include <fmt/core.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "insitu/series_state.hpp"
#include "insitu/shock_position.hpp"
#include "insitu/view_fields.hpp"
#include "insitu/vtk_pieces.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/core/derivatives.hpp"
#include "solver/core/communicator.hpp"

namespace dustlift {
namespace {

class VtkParcelWriter final : public Observer {
 public:
  explicit VtkParcelWriter(ParcelArraysOf parcels_of) : parcels_of_(std::move(parcels_of)) {
    if (!parcels_of_) throw std::invalid_argument("VtkParcelWriter: no parcel adaptor");
  }
  // A decomposed run: each rank writes its own parcels, rank 0 the .pvtp that joins them.
  bool writes_pieces() const override { return true; }

  void on_output(const StateView& view) override {
    if (!files_) files_ = make_files(view);
    if (files_->last_time_is(view.time)) return;  // on_finish right after that output
    if (view.piece == nullptr) {
      write_parcels_vtp(parcels_of_(view), files_->next_path(view.time), vtk_file_info_of(view));
      files_->commit(view.time);
      return;
    }
    // The rank's table holds copies of its neighbours' parcels: those are theirs to write.
    const ParcelArraysView all = parcels_of_(view);
    const ParcelArraysView own = kept_rows(all, view.piece->parcel_copies, own_);
    write_in_pieces(
        *files_, *view.piece, view.time, "vtp",
        [&](const std::string& path) { write_parcels_vtp(own, path, vtk_file_info_of(view)); },
        // The arrays every piece holds, from this rank's table (present even with no parcel of
        // its own).
        [&](const std::string& path, const std::vector<std::string>& sources) {
          write_parcels_pvtp(all, sources, path);
        });
  }

  std::string state_key() const override { return "parcels_vtk"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    if (files_) {
      files_->save_state(s, prefix);
    } else {
      VtkSeriesFiles("", "parcels", "vtp").save_state(s, prefix);  // nothing written yet
    }
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    restored_ = VtkSeriesFiles::read_state(s, prefix);
  }
  void on_resume(const StateView& view, const std::string& previous_output_dir) override {
    files_ = make_files(view);
    files_->resume(std::move(restored_), previous_output_dir);
    if (view.piece != nullptr) view.piece->comm->barrier();  // rank 0 has removed stale pieces
  }

 private:
  static std::unique_ptr<VtkSeriesFiles> make_files(const StateView& view) {
    if (view.piece != nullptr)
      return std::make_unique<VtkSeriesFiles>(
          piece_series_files(view.output_dir, "parcels", "vtp", *view.piece));
    return std::make_unique<VtkSeriesFiles>(view.output_dir, "parcels", "vtp");
  }

  ParcelArraysOf parcels_of_;
  std::unique_ptr<VtkSeriesFiles> files_;
  VtkSeriesFiles::State restored_;
  ParcelArraysCopy own_;  // reused: no reallocation once sized
};

class BandForceObserver final : public Observer {
 public:
  BandForceObserver(BandForceOptions options, BandParcelsOf parcels_of)
      : options_(std::move(options)),
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
    write(view);
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

  std::string state_key() const override { return "bands"; }
  void save_state(Snapshot& s, const std::string& prefix) const override {
    s.f64[prefix + "shock_times"] = trajectory_.times();
    s.f64[prefix + "shock_reaches"] = trajectory_.reaches();
    save_time(last_time_, sampled_, s, prefix + "last_sample_time");
    series_.save_state(s, prefix);
  }
  void restore_state(const Snapshot& s, const std::string& prefix) override {
    try {
      trajectory_.assign(snapshot_array(s.f64, prefix + "shock_times"),
                         snapshot_array(s.f64, prefix + "shock_reaches"));
    } catch (const std::invalid_argument& e) {
      throw SnapshotError(prefix + "shock_times/shock_reaches: " + e.what());
    }
    sampled_ = restore_time(last_time_, s, prefix + "last_sample_time");
    series_.restore_state(s, prefix);
  }
  void on_resume(const StateView& view, const std::string&) override { write(view); }

 private:
  void write(const StateView& view) {
    if (!sink_) sink_ = std::make_unique<SeriesSink>(series_sink_of(view));
    series_.write(*sink_);
  }
  void sample(const StateView& view) {
    if (sampled_ && view.time == last_time_) return;
    if (!view.grid || !view.primitives.p)
      throw std::invalid_argument("BandForceObserver: the state view has no pressure field");
    const Grid2D& grid = *view.grid;
    interior_values(grid, *view.primitives.p, pressure_);
    if (x_centers_.empty()) {
      x_centers_ = interior_centers(grid.x());
      y_centers_ = interior_centers(grid.y());
    }
    const double shock_x =
        shock_position(x_centers_, y_centers_, pressure_, options_.shock.p_ambient,
                       options_.shock.threshold, options_.shock.y_min);
    BandParcelsView parcels = parcels_of_(view);
    trajectory_.record(view.time, shock_x, max_shock_advance(grid.x()));
    arrival_.resize(parcels.count);
    band_arrival_times(trajectory_, options_.bands, parcels.initial_position.x,
                       parcels.initial_position.y, arrival_);
    parcels.arrival_time = arrival_;
    series_.add(parcels, view.time);
    sampled_ = true;
    last_time_ = view.time;
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
  std::unique_ptr<SeriesSink> sink_;
  ShockTrajectory trajectory_;
  std::vector<double> arrival_, pressure_, x_centers_, y_centers_;
  bool sampled_ = false;
  double last_time_ = 0.0;
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
