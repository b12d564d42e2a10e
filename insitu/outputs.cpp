#include "insitu/outputs.hpp"

#include <cmath>

#include "insitu/observers.hpp"
#include "solver/coupling/gas_particle_coupling.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {
namespace {

/// A force part's columns, or none when the scene does not compute it (a column of zeros
/// would read as a computed zero force).
Vec2Columns force_part(bool computed, const std::vector<double>& fx,
                       const std::vector<double>& fy) {
  return computed ? Vec2Columns{present_column(fx), present_column(fy)} : Vec2Columns{};
}
/// The force parts the coupling's models write (none without a coupling).
ForceParts force_parts_of(const StateView& v) {
  return v.coupling != nullptr ? v.coupling->force_parts() : ForceParts{};
}
Vec2Columns both(const std::vector<double>& x, const std::vector<double>& y) {
  return {present_column(x), present_column(y)};
}

/// Parcel arrays straight from the ParcelSystem (no copy): the writer reads them at outputs.
/// The force parts of effects that are off are left out; the table's attached columns marked
/// `written` are added under their names.
ParcelArraysView parcel_arrays_of(const StateView& v) {
  const ParcelSystem& p = *v.parcels;
  const ForceParts c = force_parts_of(v);
  ParcelArraysView a;
  a.count = p.size();
  // Every column present, also on a rank without parcels (present_column).
  a.position = both(p.x, p.y);
  static constexpr std::int32_t kNoId = 0;
  a.id =
      p.id.empty() ? std::span<const std::int32_t>(&kNoId, 0) : std::span<const std::int32_t>(p.id);
  a.velocity = both(p.vx, p.vy);
  a.angular_velocity = present_column(p.omega);
  a.temperature = present_column(p.temperature);
  a.diameter = present_column(p.diameter);
  a.initial_position = both(p.x_initial, p.y_initial);
  a.force_contact = both(p.contact_fx, p.contact_fy);
  a.force_drag = force_part(c.drag, p.drag_fx, p.drag_fy);
  a.force_magnus = force_part(c.magnus, p.magnus_fx, p.magnus_fy);
  a.force_pressure = force_part(c.pressure, p.pressure_fx, p.pressure_fy);
  for (std::size_t k = 0; k < p.attached_count(); ++k) {
    if (p.attached_spec(k).written)
      a.extra.push_back({p.attached_spec(k).name, present_column(p.attached(k))});
  }
  return a;
}

/// The band filter's view: the parcel table as it is (parcel order; no copy).
BandParcelsView band_arrays_of(const StateView& v) {
  const ParcelSystem& p = *v.parcels;
  BandParcelsView b;
  b.count = p.size();
  b.initial_position = {p.x_initial, p.y_initial};
  b.y = p.y;
  const ForceParts c = force_parts_of(v);
  b.force_contact = {p.contact_fx, p.contact_fy};
  b.force_drag = force_part(c.drag, p.drag_fx, p.drag_fy);
  b.force_magnus = force_part(c.magnus, p.magnus_fx, p.magnus_fy);
  b.force_pressure = force_part(c.pressure, p.pressure_fx, p.pressure_fy);
  b.particle_rotation = p.omega;
  if (v.coupling != nullptr) {
    b.relative_rotation = p.column(v.coupling->relative_rotation_column());
    b.gas_rotation = p.column(v.coupling->gas_rotation_column());
  }
  return b;
}

}  // namespace

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
    observers.push_back(make_catalyst_observer(scene, output_dir, scene.particles.enabled ? parcel_arrays_of : nullptr));
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
    if (scene.particles.layer.y_max <= y.center(y.cells() - 1)) shock.y_min = scene.particles.layer.y_max;
  }
  if (ic.axis == 'x') {
    // A Riemann start with the high pressure on the right sends its shock to -x: skip.
    const bool rightward = ic.kind != InitialCondition::Kind::Riemann || ic.left.p > ic.right.p;
    if (rightward) observers.push_back(make_shock_position_observer(shock));
  }
  if (!out.probes.empty()) observers.push_back(make_probe_observer({out.probes, out.probe_interval}));
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
  observers.push_back(make_near_layer_observer({L.x_min + 0.25 * len, L.x_min + 0.5 * len, L.y_min, L.y_max + 5e-3}));

  if (!out.bands.empty() && ic.axis == 'x') {
    BandForceOptions bands;
    for (const auto& b : out.bands) bands.bands.push_back({b.name, b.x_min, b.x_max, b.y_min, b.y_max});
    bands.averaging.tau_min = 0.0;
    bands.averaging.tau_max = out.band_duration;
    bands.averaging.bin_width = out.band_bin_width;
    bands.averaging.contact_window = out.contact_window;
    bands.shock = shock;
    bands.sample_every_step = true;
    observers.push_back(make_band_force_observer(bands, band_arrays_of));
  }
  return observers;
}

}  // namespace dustlift
