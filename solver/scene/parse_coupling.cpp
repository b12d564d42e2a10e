// [coupling]: which gas-particle effects act (paper Table 1, eqs. 7-16) and their options.
#include <fmt/format.h>

#include <algorithm>

#include "solver/core/grid.hpp"
#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {

void parse_coupling(TableReader t, CouplingConfig& c, const DemConfig& dem,
                    const GridConfig& grid) {
  t.expect_keys({"two_way", "drag", "compressibility_correction", "volume_fraction_correction",
                 "volume_fraction_cap", "magnus", "magnus_coefficient", "magnus_convention",
                 "lun_liu", "pressure_force", "added_mass", "added_mass_volume_fraction",
                 "added_mass_fluid_acceleration", "rotation_torque", "torque_stokes_below",
                 "heat_transfer", "interpolation", "influence_width", "max_volume_fraction",
                 "finite_size"});
  if (!dem.enabled) {
    if (t.present() && !dem.switched_off)
      t.fail("two_way", "a [coupling] section needs [particles]");
    return;
  }
  c.two_way = t.boolean("two_way", c.two_way);
  c.drag = t.boolean("drag", c.drag);
  c.compressibility_correction =
      t.boolean("compressibility_correction", c.compressibility_correction);
  const auto vf = t.choice("volume_fraction_correction", "sangani",
                           {"sangani", "osnes", "tenneti", "linear", "none"});
  using Closure = aero::VolumeFractionCorrection::Kind;
  c.volume_fraction.kind = vf == "sangani"   ? Closure::Sangani
                           : vf == "osnes"   ? Closure::Osnes
                           : vf == "tenneti" ? Closure::Tenneti
                           : vf == "linear"  ? Closure::Linear
                                             : Closure::None;
  c.volume_fraction.phi_cap = t.number("volume_fraction_cap", 1.0, Range::open_closed(0.0, 1.0));
  c.magnus = t.boolean("magnus", c.magnus);
  c.magnus_coefficient =
      t.number("magnus_coefficient", c.magnus_coefficient, Range::non_negative());
  const auto conv = t.choice("magnus_convention", "paper", {"paper", "standard"});
  c.magnus_convention =
      conv == "paper" ? aero::MagnusConvention::Paper : aero::MagnusConvention::Standard;
  c.lun_liu = t.boolean("lun_liu", c.lun_liu);
  c.pressure_force = t.boolean("pressure_force", c.pressure_force);
  c.added_mass = t.boolean("added_mass", c.added_mass);
  const auto am = t.choice("added_mass_volume_fraction", "beguin", {"beguin", "zuber", "none"});
  c.added_mass_volume_fraction = am == "beguin"  ? aero::AddedMassVolumeFraction::Beguin
                                 : am == "zuber" ? aero::AddedMassVolumeFraction::Zuber
                                                 : aero::AddedMassVolumeFraction::None;
  const auto fa =
      t.choice("added_mass_fluid_acceleration", "resolved", {"resolved", "pressure_gradient"});
  c.added_mass_fluid_acceleration = fa == "resolved" ? aero::FluidAcceleration::Resolved
                                                     : aero::FluidAcceleration::PressureGradient;
  c.rotation_torque = t.boolean("rotation_torque", c.rotation_torque);
  c.torque_stokes_below =
      t.number("torque_stokes_below", c.torque_stokes_below, Range::non_negative());
  c.heat_transfer = t.boolean("heat_transfer", c.heat_transfer);
  c.finite_size = t.boolean("finite_size", c.finite_size);
  const auto rule = t.choice("interpolation", "triangle", {"triangle", "bilinear"});
  c.interpolation = rule == "triangle" ? InterpolationRule::Triangle : InterpolationRule::Bilinear;
  const double min_cell = min_cell_width(grid);
  // Checked before influence_width, whose default is the parcel diameter: the message then
  // names the key the user set. Relative tolerance: a 2 mm parcel fits a 2.0 m / 1000 cell.
  // A particle larger than the cells is for a one-way run that averages the undisturbed flow
  // over it (finite_size): the gas does not feel what it would deposit.
  const bool resolved_sphere = c.finite_size && !c.two_way;
  if (dem.parcel_diameter > min_cell * (1.0 + kCellTolerance) && !resolved_sphere) {
    throw SceneError(t.file() + ": key 'particles.parcel_diameter': parcels of " +
                     fmt::format("{:.9g}", dem.parcel_diameter) +
                     " m are larger than the smallest grid cell (" +
                     fmt::format("{:.9g}", min_cell) +
                     " m), which breaks the unresolved-particle model (eqs. 12-16)");
  }
  c.influence_width =
      t.derived_number("influence_width", dem.parcel_diameter,
                       "particles.parcel_diameter (Table 2)", Range::non_negative());
  if (c.influence_width > min_cell * (1.0 + kCellTolerance)) {
    t.fail("influence_width", fmt::format("{:.9g} m must not exceed the smallest cell ({:.9g} m)",
                                          c.influence_width, min_cell));
  }
  c.max_volume_fraction =
      t.number("max_volume_fraction", c.max_volume_fraction, Range::open(0.0, 1.0));
  t.finish();
}

}  // namespace dustlift::scene_detail
