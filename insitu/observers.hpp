#pragma once
// Factories for the in-situ observers. VTK- and HDF5-free: app/ and sim/ include this
// header only; the implementations live in insitu/*.cpp.
#include <functional>
#include <memory>
#include <vector>

#include "insitu/band_average.hpp"
#include "insitu/dust_cloud.hpp"
#include "insitu/entrainment.hpp"
#include "insitu/parcel_arrays.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

/// Writes OUTDIR/vtk/gas_NNNNNN.vtr at each output and rewrites OUTDIR/gas.pvd
/// (timestep = simulated time in s). Needs StateView::gas (Mach uses sound_speed).
std::unique_ptr<Observer> make_vtk_gas_writer();

/// Same with the sound speed c(view, i, j) supplied by the caller (tests, or a scene
/// whose gas model is not a GasSolver); make_vtk_gas_writer() passes gas->sound_speed.
using SoundSpeedFunction = std::function<double(const StateView&, int, int)>;
std::unique_ptr<Observer> make_vtk_gas_writer(SoundSpeedFunction sound_speed);

struct SurfaceHeightOptions {
  double threshold = 1e-4;         ///< alpha_p level of the surface (paper section 3.2)
  std::vector<double> stations_x;  ///< m; x of the station columns (may be empty)
};
/// Dust-surface height h(x): series surface_height (time_s, x_m, height_m; columns with no
/// particles skipped) and surface_height_stations (time_s, one height per station, NaN
/// where no particles).
std::unique_ptr<Observer> make_surface_height_observer(SurfaceHeightOptions options = {});

struct ShockPositionOptions {
  double threshold = 0.05;  ///< relative pressure rise that marks the shock
  double p_ambient = 0.0;   ///< Pa; 0: each row's rightmost (downstream) cell pressure
  double y_min = 0.0;       ///< m; rows with centre below y_min are ignored
  bool every_step = false;  ///< sample at every step (cheap) instead of outputs only
};
/// Shock position: series shock_position (time_s, x_m), rightmost x over rows with
/// y >= y_min where p > p_ambient (1 + threshold), interpolated between cell centres.
std::unique_ptr<Observer> make_shock_position_observer(ShockPositionOptions options = {});

/// Parcel writer: OUTDIR/vtk/parcels_NNNNNN.vtp + OUTDIR/parcels.pvd at each output.
/// `parcels_of` adapts the state (e.g. its ParcelSystem) to array views; it is called at
/// outputs only and the spans must stay valid until it is called again.
using ParcelArraysOf = std::function<ParcelArraysView(const StateView&)>;
std::unique_ptr<Observer> make_vtk_parcel_writer(ParcelArraysOf parcels_of);

struct BandForceOptions {
  std::vector<Band> bands;        ///< one series forces_<name> per band
  BandAverageOptions averaging;   ///< tau bins and the contact-force window
  ShockPositionOptions shock;     ///< how the shock arrival is detected
  bool sample_every_step = true;  ///< false: sample at outputs only
};
/// Band-averaged force histories (series forces_<band>): at every step (or output) finds
/// the shock position from the pressure field and records it (ShockTrajectory); a band
/// parcel's arrival time is when the shock first reached its initial x, and the band's
/// parcels are binned by t - t_arrival. `parcels_of` supplies everything but arrival_time,
/// in any parcel order (the DEM re-sorts its parcels).
using BandParcelsOf = std::function<BandParcelsView(const StateView&)>;
std::unique_ptr<Observer> make_band_force_observer(BandForceOptions options,
                                                   BandParcelsOf parcels_of);

/// Point probes (OpenFOAM's `probes`): the gas values of the cell holding each probe point,
/// at t = 0 and then after every step (interval 0) or after the first step at or past each
/// multiple of `interval`. Series probes: time_s, then <probe>_<field> per probe and field.
struct ProbeOptions {
  std::vector<ProbeConfig> probes;
  double interval = 0.0;  ///< s of simulated time; 0: every step
};
std::unique_ptr<Observer> make_probe_observer(ProbeOptions options);

/// Series parcel_fronts: time_s, x_min_m, x_p01_m, x_p99_m, x_max_m at each output: the
/// outermost parcels in x and the x below which 1 % and 99 % of the real particles lie
/// (parcel_fronts.hpp). A particle curtain's upstream and downstream fronts.
std::unique_ptr<Observer> make_parcel_fronts_observer(const Scene& scene);

/// Series dust_cloud (docs/output.md): the lifted dust at each output (dust_cloud.hpp), its
/// heights, temperatures, its filtered concentration's explosible band, the entrainment rate
/// and the fluxes through `heights` (entrainment.hpp), and the distances of the first and the
/// densest lifted grid column behind the shock (found as the shock-position observer finds
/// it; NaN when `shock_along_x` is false or no shock is in the domain). The lifted shares
/// divide by the layer's mass at the first output, kept in checkpoints. Series
/// dust_concentration_histogram (lifted mass per concentration bin) and dust_entrainment
/// (per stretch of channel). Logs quantum_warning() once per run segment.
std::unique_ptr<Observer> make_dust_cloud_observer(DustCloudOptions options,
                                                   EntrainmentOptions entrainment,
                                                   ShockPositionOptions shock, bool shock_along_x);

/// Window of the near-layer field series (paper Fig. 13).
struct NearLayerOptions {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;  ///< m
};
/// Series near_layer: time_s, x_m, y_m, u, v, vorticity (omega_z), alpha_p of every cell whose
/// centre lies in the window, at each output time.
std::unique_ptr<Observer> make_near_layer_observer(NearLayerOptions options);

/// ParaView Catalyst (docs/catalyst.md): runs the scene's [insitu.catalyst] scripts on the
/// channels "gas" and "parcels" at its cadence and always on the last step. Loads the adaptor
/// module here; throws SceneError (exit 2, before anything is written) when this build has no
/// Catalyst, the module is missing, or there is neither a display nor Xvfb.
std::unique_ptr<Observer> make_catalyst_observer(const Scene& scene, const std::string& output_dir,
                                                 ParcelArraysOf parcels_of);

}  // namespace dustlift
