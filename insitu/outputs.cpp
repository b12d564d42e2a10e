#include "insitu/outputs.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "insitu/observers.hpp"
#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {
namespace {

/// The force part's two columns, when an effect of the run computes it (its effect attached
/// them); absent otherwise (a column of zeros would read as a computed zero force).
Vec2Columns force_part(const ParcelSystem& p, ForcePart part) {
  const ParcelColumn x = p.find_part(part, 0), y = p.find_part(part, 1);
  if (!x.valid() || !y.valid()) return Vec2Columns{};
  return Vec2Columns{present_column(p.column(x)), present_column(p.column(y))};
}

/// Parcel arrays straight from the parcel table (no copy): its written columns, each under
/// its point array's name (two components make a vector), in the table's order; the force
/// parts of effects that are off do not exist. Every column is present, also on a rank
/// without parcels (present_column).
ParcelArraysView parcel_arrays_of(const StateView& v) {
  const ParcelSystem& p = *v.parcels;
  ParcelArraysView a;
  a.count = p.size();
  static constexpr std::int32_t kNoId = 0;
  a.id =
      p.id.empty() ? std::span<const std::int32_t>(&kNoId, 0) : std::span<const std::int32_t>(p.id);
  p.for_each_column([&](const ParcelColumnSpec& c, const auto& values) {
    if constexpr (std::is_same_v<std::decay_t<decltype(values)>, std::vector<double>>) {
      if (!c.written) return;
      const std::string& name = c.written_as.empty() ? c.name : c.written_as;
      if (name == "position") {
        (c.component == 0 ? a.position.x : a.position.y) = present_column(values);
      } else if (c.component == 1 && !a.arrays.empty() && a.arrays.back().name == name) {
        a.arrays.back().y = present_column(values);
      } else {
        a.add(name, present_column(values));
      }
    }
  });
  return a;
}

/// The band filter's view: the parcel table as it is (parcel order; no copy).
BandParcelsView band_arrays_of(const StateView& v) {
  const ParcelSystem& p = *v.parcels;
  BandParcelsView b;
  b.count = p.size();
  b.initial_position = {p.x_initial, p.y_initial};
  b.y = p.y;
  b.force_contact = {p.contact_fx, p.contact_fy};
  b.force_drag = force_part(p, ForcePart::Drag);
  b.force_magnus = force_part(p, ForcePart::Magnus);
  b.force_pressure = force_part(p, ForcePart::Pressure);
  b.particle_rotation = p.omega;
  if (v.coupling != nullptr) {
    b.relative_rotation = p.column(v.coupling->relative_rotation_column());
    b.gas_rotation = p.column(v.coupling->gas_rotation_column());
  }
  return b;
}

}  // namespace

DustCloudOptions dust_cloud_options(const Scene& scene) {
  const OutputConfig& out = scene.output;
  const LayerConfig& L = scene.particles.layer;
  DustCloudOptions cloud;
  cloud.layer_top = L.y_max;
  cloud.lift_height = out.cloud_lift_height;
  cloud.top_concentration = out.cloud_top_concentration;
  cloud.classes = std::max<int>(1, static_cast<int>(scene.particles.size_classes.size()));
  cloud.filter_width = out.cloud_filter_width;
  cloud.x_origin = L.x_min;
  cloud.x_start = scene.grid.x.start;
  cloud.x_end = scene.grid.x.end;
  cloud.y_end = scene.grid.y.end;
  cloud.explosible_lower = out.explosible_lower;
  cloud.explosible_upper = out.explosible_upper;
  cloud.fines_diameter = out.fines_diameter;
  cloud.heights = out.entrainment_heights;
  return cloud;
}

EntrainmentOptions entrainment_options(const Scene& scene) {
  const LayerConfig& L = scene.particles.layer;
  EntrainmentOptions e;
  e.layer_top = L.y_max;
  e.lift_height = scene.output.cloud_lift_height;
  e.heights = scene.output.entrainment_heights;
  e.bin_width = scene.output.entrainment_bin_width;
  e.x_origin = L.x_min;
  e.x_start = scene.grid.x.start;
  e.x_end = scene.grid.x.end;
  return e;
}

std::vector<std::unique_ptr<Observer>> make_output_observers(const Scene& scene,
                                                             const std::string& output_dir,
                                                             bool piece_writers_only) {
  std::vector<std::unique_ptr<Observer>> observers;
  if (piece_writers_only) {
    if (scene.output.vtk) observers.push_back(make_vtk_gas_writer());
    if (scene.output.vtk && scene.particles.enabled)
      observers.push_back(make_vtk_parcel_writer(parcel_arrays_of));
    return observers;
  }
  // Effects-off rule: without the section no Catalyst code is loaded or run.
  if (scene.insitu.catalyst.enabled) {
    observers.push_back(make_catalyst_observer(
        scene, output_dir, scene.particles.enabled ? parcel_arrays_of : nullptr));
  }
  const OutputConfig& out = scene.output;
  if (out.vtk) observers.push_back(make_vtk_gas_writer());

  // Shock position along x: the pre-shock pressure is known for shock and Riemann
  // starts (the state the shock runs into); otherwise each row's downstream cell is used.
  // Over a dust layer only the rows above it are searched (the paper's shock "above the layer").
  const InitialCondition& ic = scene.initial;
  ShockPositionOptions shock;
  shock.threshold = out.shock_threshold;
  if (ic.kind == InitialCondition::Kind::Shock) shock.p_ambient = ic.state.p;
  if (ic.kind == InitialCondition::Kind::Riemann) shock.p_ambient = ic.right.p;
  // A layer that fills the channel (a bed across a shock tube) leaves no row above it: then
  // every row is searched.
  if (scene.particles.enabled) {
    const Axis y(build_axis_nodes(scene.grid.y), 0);
    if (scene.particles.layer.y_max <= y.center(y.cells() - 1))
      shock.y_min = scene.particles.layer.y_max;
  }
  // A Riemann start with the high pressure on the right sends its shock to -x: skip.
  const bool rightward =
      ic.axis == 'x' && (ic.kind != InitialCondition::Kind::Riemann || ic.left.p > ic.right.p);
  if (rightward) observers.push_back(make_shock_position_observer(shock));
  if (!out.probes.empty())
    observers.push_back(make_probe_observer({out.probes, out.probe_interval}));
  if (!scene.particles.enabled) return observers;

  if (out.vtk) observers.push_back(make_vtk_parcel_writer(parcel_arrays_of));
  SurfaceHeightOptions surface;
  surface.threshold = out.surface_threshold;
  surface.stations_x = out.surface_stations;
  observers.push_back(make_surface_height_observer(surface));

  // Fig. 13: u and vorticity from the floor to 5 mm above the layer, over the second
  // quarter of the layer (the paper's analysis region, 100-200 mm of 400 mm).
  const LayerConfig& L = scene.particles.layer;
  const double len = L.x_max - L.x_min;
  observers.push_back(make_near_layer_observer(
      {L.x_min + 0.25 * len, L.x_min + 0.5 * len, L.y_min, L.y_max + 5e-3}));

  if (!out.bands.empty() && ic.axis == 'x') {
    BandForceOptions bands;
    for (const auto& b : out.bands)
      bands.bands.push_back({b.name, b.x_min, b.x_max, b.y_min, b.y_max});
    bands.averaging.tau_min = 0.0;
    bands.averaging.tau_max = out.band_duration;
    bands.averaging.bin_width = out.band_bin_width;
    bands.averaging.contact_window = out.contact_window;
    bands.shock = shock;
    bands.sample_every_step = true;
    observers.push_back(make_band_force_observer(bands, band_arrays_of));
  }
  if (out.parcel_fronts) observers.push_back(make_parcel_fronts_observer(scene));
  if (out.dust_cloud)
    observers.push_back(make_dust_cloud_observer(dust_cloud_options(scene),
                                                 entrainment_options(scene), shock, rightward));
  return observers;
}

}  // namespace dustlift
