// The scene's ParcelSystem factory (generated layer or layer file) and settling under gravity.
#include "solver/dem/layer_generator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/dem/class_columns.hpp"
#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/size_distribution.hpp"

namespace dustlift {
namespace {

ParcelInit parcel_of(const DemConfig& cfg, double x, double y, double n_real) {
  ParcelInit p;
  p.x = x;
  p.y = y;
  p.diameter = cfg.parcel_diameter;
  p.real_diameter = cfg.particle_diameter;
  p.density = cfg.density;
  p.n_real = n_real;
  p.temperature = cfg.initial_temperature;
  return p;
}

/// Classes with parcels of their own sizes: columns of one class each (class_columns.hpp).
void add_class_columns(const DemConfig& cfg, ParcelSystem& system) {
  const ClassColumns plan = plan_class_columns(cfg);
  const ClassColumnParcels placed = place_class_columns(cfg, plan);
  system.reserve(placed.x.size());
  for (std::size_t i = 0; i < placed.x.size(); ++i) {
    const auto k = static_cast<std::size_t>(placed.size_class[i]);
    ParcelInit p = parcel_of(cfg, placed.x[i], placed.y[i], plan.real_per_parcel[k]);
    p.diameter = cfg.size_classes[k].parcel_diameter;
    p.real_diameter = cfg.size_classes[k].diameter;
    p.size_class = placed.size_class[i];
    system.add_parcel(p);
  }
}

void add_generated_layer(const DemConfig& cfg, ParcelSystem& system) {
  if (has_class_parcels(cfg.size_classes)) {
    add_class_columns(cfg, system);
    return;
  }
  const LayerPositions pos = generate_layer(cfg.layer, cfg.parcel_diameter);
  const double area = (cfg.layer.x_max - cfg.layer.x_min) * (cfg.layer.y_max - cfg.layer.y_min);
  // The plan's count: a loose top leaves the rows below at the layer's volume_fraction.
  const double n_parcels = static_cast<double>(pos.lattice.n_parcels);
  const double n_real = cfg.real_per_parcel > 0.0
                            ? cfg.real_per_parcel
                            : derived_real_per_parcel(cfg.layer.volume_fraction, area, n_parcels,
                                                      cfg.particle_diameter);
  system.reserve(pos.x.size());
  if (cfg.size_classes.empty()) {
    for (std::size_t i = 0; i < pos.x.size(); ++i)
      system.add_parcel(parcel_of(cfg, pos.x[i], pos.y[i], n_real));
    return;
  }
  // Polydisperse: every parcel holds the same solid volume alpha_p A / N, so a class's share
  // of the parcels is its share of the mass, and a parcel of class k holds
  // alpha_p A / (N V_p(d_k)) real particles (docs/dem.md, "Polydisperse layers").
  const std::vector<int> classes = layer_size_classes(cfg, pos.x.size());
  for (std::size_t i = 0; i < pos.x.size(); ++i) {
    const auto k = static_cast<std::size_t>(classes[i]);
    const double d = cfg.size_classes[k].diameter;
    ParcelInit p =
        parcel_of(cfg, pos.x[i], pos.y[i],
                  derived_real_per_parcel(cfg.layer.volume_fraction, area, n_parcels, d));
    p.real_diameter = d;
    p.size_class = classes[i];
    system.add_parcel(p);
  }
}

/// The file's parcels; one of diameter D_i holds (D_i / D)^2 times real_per_parcel (eq. 11).
void add_file_layer(const DemConfig& cfg, ParcelSystem& system) {
  const double n_ref = cfg.real_per_parcel > 0.0
                           ? cfg.real_per_parcel
                           : equal_fraction_real_per_parcel(cfg.parcel_diameter, cfg.particle_diameter);
  system.reserve(cfg.layer_parcels.size());
  for (const PlacedParcel& f : cfg.layer_parcels) {
    const double scale = f.diameter / cfg.parcel_diameter;
    ParcelInit p = parcel_of(cfg, f.x, f.y, n_ref * scale * scale);
    if (!cfg.size_classes.empty()) {
      // Its own particles: the solid volume it would hold of particles.diameter.
      const double d = f.particle_diameter > 0.0 ? f.particle_diameter : cfg.particle_diameter;
      p.real_diameter = d;
      p.size_class = size_class_of(cfg.size_classes, d);
      p.n_real = same_volume_real_per_parcel(p.n_real, cfg.particle_diameter, d);
    }
    p.diameter = f.diameter;
    p.vx = f.vx;
    p.vy = f.vy;
    p.omega = f.omega;
    p.temperature = f.temperature;
    system.add_parcel(p);
  }
}

}  // namespace

std::vector<int> layer_size_classes(const DemConfig& cfg, std::size_t placed) {
  std::vector<double> fractions;
  for (const SizeClass& c : cfg.size_classes) fractions.push_back(c.mass_fraction);
  return shuffled_classes(largest_remainder_counts(static_cast<std::int64_t>(placed), fractions),
                          cfg.layer.seed);
}

std::string describe_size_classes(const DemConfig& cfg) {
  if (cfg.size_classes.empty()) return {};
  if (has_class_parcels(cfg.size_classes))
    return describe_class_columns(cfg, plan_class_columns(cfg));
  std::vector<std::int64_t> counts(cfg.size_classes.size(), 0);
  if (cfg.layer.arrangement == LayerArrangement::File) {
    for (const PlacedParcel& p : cfg.layer_parcels) {
      const int k =
          size_class_of(cfg.size_classes,
                        p.particle_diameter > 0.0 ? p.particle_diameter : cfg.particle_diameter);
      if (k >= 0) ++counts[static_cast<std::size_t>(k)];
    }
  } else {
    const std::size_t placed = generate_layer(cfg.layer, cfg.parcel_diameter).x.size();
    for (int k : layer_size_classes(cfg, placed)) ++counts[static_cast<std::size_t>(k)];
  }
  std::ostringstream s;
  s.precision(4);
  s << "size classes (" << cfg.size_classes.size() << "):";
  for (std::size_t k = 0; k < cfg.size_classes.size(); ++k) {
    s << (k ? ";" : "") << " " << cfg.size_classes[k].diameter * 1e6 << " um, " << counts[k]
      << " parcels, mass fraction " << cfg.size_classes[k].mass_fraction;
  }
  return s.str();
}

std::string describe_layer(const DemConfig& cfg) {
  const LayerConfig& L = cfg.layer;
  std::ostringstream s;
  s.precision(4);
  s << "layer: " << layer_arrangement_name(L.arrangement);
  if (has_class_parcels(cfg.size_classes)) {
    // The plan and the classes are one description (describe_size_classes).
    s << ", " << describe_size_classes(cfg);
    if (layer_settles(L)) s << "; settled under gravity before t = 0";
    return s.str();
  }
  if (L.arrangement == LayerArrangement::File) {
    s << ", " << cfg.layer_parcels.size() << " parcels from the layer file";
  } else {
    const LayerLattice plan = plan_layer(L, cfg.parcel_diameter);
    const double area = (L.x_max - L.x_min) * (L.y_max - L.y_min);
    s << ", " << plan.rows << " rows x " << plan.cols << " columns, pitch " << plan.pitch_x * 1e6 << " x "
      << plan.pitch_y * 1e6 << " um, nearest centres " << plan_nearest_distance(L, plan) * 1e6 << " um, "
      << plan.n_parcels << " parcels, areal fraction "
      << areal_fraction(static_cast<double>(plan.n_parcels), cfg.parcel_diameter, area);
    if (L.loose_top_rows > 0) {
      const auto placed = generate_layer(L, cfg.parcel_diameter).x.size();
      s << "; loose top: the top " << L.loose_top_rows << " rows at fill " << L.loose_top_fill
        << ", " << placed << " parcels placed";
    }
  }
  if (layer_settles(L)) s << "; settled under gravity before t = 0";
  if (!cfg.size_classes.empty()) s << "; " << describe_size_classes(cfg);
  return s.str();
}

std::string describe_bed(const ParcelSystem& system, const LayerConfig& layer) {
  double top = layer.y_min, covered = 0.0;
  for (std::size_t i = 0; i < system.size(); ++i) {
    top = std::max(top, system.y[i] + system.radius[i]);
    covered += disc_area(system.diameter[i]);
  }
  std::ostringstream s;
  s.precision(4);
  s << "bed: " << system.size() << " parcels, highest top at y = " << top * 1e3 << " mm (layer rectangle top "
    << layer.y_max * 1e3 << " mm), areal fraction below it " << covered / ((layer.x_max - layer.x_min) * (top - layer.y_min));
  return s.str();
}

ParcelSystem make_layer_system(const DemConfig& cfg) {
  ParcelSystem system(cfg);
  if (cfg.layer.arrangement == LayerArrangement::File) {
    add_file_layer(cfg, system);
  } else {
    add_generated_layer(cfg, system);
  }
  if (layer_settles(cfg.layer)) {
    // Settle until the bed is quiet: kinetic energy per parcel below a millionth of the
    // work gravity does on one parcel falling one diameter.
    const double m = system.mass.empty() ? 0.0 : system.mass[0];
    const double ke_tol = 1e-6 * m * 9.81 * cfg.parcel_diameter;
    settle_under_gravity(system, 9.81, ke_tol, 1.0);
    // Restart the parcels' history from the settled bed.
    system.x_initial = system.x;
    system.y_initial = system.y;
  }
  return system;
}

double settle_under_gravity(ParcelSystem& system, double g, double ke_per_parcel, double max_time) {
  const double gx = system.config().gravity_x, gy = system.config().gravity_y;
  system.set_gravity(0.0, -g);
  const double chunk = 200.0 * system.stable_time_step();
  const double n = static_cast<double>(std::max<std::size_t>(1, system.size()));
  double t = 0.0;
  // Quiet means slow AND resting on something (a bed that has not started falling is slow too).
  while (t < max_time) {
    system.advance(chunk);
    t += chunk;
    if (system.kinetic_energy() / n < ke_per_parcel && system.contact_pair_count() > 0) break;
  }
  std::fill(system.vx.begin(), system.vx.end(), 0.0);
  std::fill(system.vy.begin(), system.vy.end(), 0.0);
  std::fill(system.omega.begin(), system.omega.end(), 0.0);
  system.set_gravity(gx, gy);
  return t;
}

}  // namespace dustlift
