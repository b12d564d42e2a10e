// ParcelSystem: construction, sub-stepping (eqs. 17–18) and energy diagnostics.
#include "solver/dem/parcel_system.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "solver/dem/contact_effects/contact_list.hpp"

namespace dustlift {

ParcelSystem::ParcelSystem(const DemConfig& cfg) : cfg_(cfg) {
  const DemDomain& d = cfg_.domain;
  if (!(d.x_max > d.x_min) || !(d.y_max > d.y_min)) {
    throw std::invalid_argument("ParcelSystem: empty DEM domain");
  }
  if (d.periodic_x && (d.wall_left || d.wall_right)) {
    throw std::invalid_argument("ParcelSystem: periodic x excludes left/right walls");
  }
  length_x_ = d.x_max - d.x_min;
  skin_ = cfg_.skin * cfg_.parcel_diameter;
  if (cfg_.contact.restitution > 0.0)
    pair_damping_factor_ = restitution_damping_factor(cfg_.contact.restitution);
  if (cfg_.wall_contact.restitution > 0.0)
    wall_damping_factor_ = restitution_damping_factor(cfg_.wall_contact.restitution);
  // The farthest any active contact unit acts beyond touching.
  for_each_contact_unit([&]<class U>(const U*) {
    if (!U::active(cfg_)) return;
    pair_reach_ = std::max(pair_reach_, U::pair_reach(cfg_));
    wall_reach_ = std::max(wall_reach_, U::wall_reach(cfg_));
  });
}

EulerArrays ParcelSystem::euler_arrays() {
  return EulerArrays{x.data(),
                     y.data(),
                     vx.data(),
                     vy.data(),
                     omega.data(),
                     temperature.data(),
                     inv_mass_real.data(),
                     inv_inertia_real.data(),
                     contact_fx.data(),
                     contact_fy.data(),
                     contact_torque.data(),
                     x_build.data(),
                     y_build.data(),
                     inv_skin2.data(),
                     cfg_.gravity_x,
                     cfg_.gravity_y,
                     1.0 / cfg_.heat_capacity};
}

void ParcelSystem::reserve(std::size_t n) {
  for_each_column([n](const ParcelColumnSpec& s, auto& v) {
    if (s.flow == ColumnFlow::Carried) v.reserve(n * static_cast<std::size_t>(s.per_parcel));
  });
}

void ParcelSystem::add_parcel(const ParcelInit& p) {
  if (!(p.diameter > 0.0) || !(p.real_diameter > 0.0) || !(p.n_real > 0.0) || !(p.density > 0.0)) {
    throw std::invalid_argument(
        "ParcelSystem::add_parcel: diameter, density and n_real must be > 0");
  }
  // Real particle: sphere of the real diameter. Parcel: n_real of them (eq. 11, §4); its
  // rotational inertia is that of a cylinder of the parcel diameter, I = m r^2 / 2.
  const double m_real =
      p.density * std::numbers::pi * p.real_diameter * p.real_diameter * p.real_diameter / 6.0;
  const double r = 0.5 * p.diameter;
  const double I_real = 0.5 * m_real * r * r;
  const std::size_t i = size();
  append_zero_row();
  id[i] = static_cast<std::int32_t>(i);
  x[i] = x_initial[i] = x_build[i] = p.x;
  y[i] = y_initial[i] = y_build[i] = p.y;
  vx[i] = p.vx;
  vy[i] = p.vy;
  omega[i] = p.omega;
  temperature[i] = p.temperature;
  diameter[i] = p.diameter;
  real_diameter[i] = p.real_diameter;
  size_class[i] = static_cast<double>(p.size_class);
  radius[i] = r;
  mass[i] = p.n_real * m_real;
  inertia[i] = p.n_real * I_real;
  n_real[i] = p.n_real;
  inv_mass_real[i] = 1.0 / m_real;
  inv_inertia_real[i] = 1.0 / I_real;
  // A new parcel has no neighbour slots yet: the next step rebuilds the list.
  nbr_offset.clear();
  nbr_index.clear();
  nbr_image.clear();
  nbr_delta.clear();
  needs_rebuild_ = true;
  counts_known_ = false;
}

ParcelInternals ParcelSystem::internals() const {
  ParcelInternals s;
  s.needs_rebuild = needs_rebuild_;
  s.time = time_;
  s.steps = steps_;
  s.rebuilds = rebuilds_;
  s.gravity_x = cfg_.gravity_x;
  s.gravity_y = cfg_.gravity_y;
  return s;
}

void ParcelSystem::restore_internals(const ParcelInternals& s) {
  const std::size_t n = size();
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("ParcelSystem::restore_internals: " + what);
  };
  bool made = true;  // every rebuilt column made (else a rebuild must be pending)
  for_each_column([&](const ParcelColumnSpec& c, const auto& v) {
    const std::size_t rows = n * static_cast<std::size_t>(c.per_parcel);
    if (c.flow == ColumnFlow::Carried) require(v.size() == rows, c.name + " has the wrong length");
    if (c.flow == ColumnFlow::Rebuilt) {
      require(v.size() == rows || v.empty(), c.name + " has the wrong length");
      made = made && v.size() == rows;
    }
  });
  require(made || s.needs_rebuild, "half_skin or wall_mask missing but no rebuild pending");
  for (double h : half_skin) require(h > 0.0 && std::isfinite(h), "half_skin must be positive");
  for (std::uint8_t m : wall_mask) require(m < (1u << kWallCount), "wall_mask out of range");
  for (std::int32_t i : id)
    require(i >= 0 && static_cast<std::size_t>(i) < n, "parcel id out of range");
  // The contact history must index the parcels it was saved with.
  if (!nbr_offset.empty()) {
    require(nbr_offset.size() == n + 1 && nbr_offset.front() == 0,
            "nbr_offset has the wrong length");
    for (std::size_t i = 0; i < n; ++i)
      require(nbr_offset[i] <= nbr_offset[i + 1], "nbr_offset not monotone");
    const auto slots = static_cast<std::size_t>(nbr_offset[n]);
    require(nbr_index.size() == slots && nbr_image.size() == slots && nbr_delta.size() == slots,
            "neighbour slots have the wrong length");
    for (std::int32_t j : nbr_index)
      require(j >= 0 && static_cast<std::size_t>(j) < n, "nbr_index out of range");
    for (std::int8_t im : nbr_image) require(im >= -1 && im <= 1, "nbr_image out of range");
  } else {
    require(nbr_index.empty() && nbr_image.empty() && nbr_delta.empty(),
            "neighbour slots without offsets");
    require(s.needs_rebuild, "no neighbour list but no rebuild pending");
  }
  inv_skin2.resize(half_skin.size());
  for (std::size_t i = 0; i < half_skin.size(); ++i)
    inv_skin2[i] = 1.0 / (half_skin[i] * half_skin[i]);
  needs_rebuild_ = s.needs_rebuild;
  counts_known_ = false;
  // The next rebuild lists every parcel: what the lists were made from is not saved.
  near_fast_before_.clear();
  listed_geometry_ = {};
  time_ = s.time;
  steps_ = s.steps;
  rebuilds_ = s.rebuilds;
  cfg_.gravity_x = s.gravity_x;
  cfg_.gravity_y = s.gravity_y;
}

double ParcelSystem::stable_time_step() const {
  double m_min = std::numeric_limits<double>::infinity();
  for (double im : inv_mass_real) m_min = std::min(m_min, 1.0 / im);
  const ContactParams& a = cfg_.contact;
  const ContactParams& b = cfg_.wall_contact;
  const double k_max = std::max({a.k_n, a.k_t, b.k_n, b.k_t});
  if (ranks_ != nullptr) m_min = ranks_->min(m_min);  // the same sub-steps on every rank
  return cfg_.courant * std::sqrt(m_min / k_max);
}

int ParcelSystem::substeps_for(double dt_total) const {
  return std::max(1, static_cast<int>(std::ceil(dt_total / stable_time_step() * (1.0 - 1e-12))));
}

int ParcelSystem::advance(double dt_total, const SubstepHook& hook) {
  if (!(dt_total > 0.0)) return 0;
  const int n = substeps_for(dt_total);
  const double dt = dt_total / n;
  const double t0 = time_;
  update_stepped_count();
  for (int k = 0; k < n; ++k) {
    if (hook) hook(*this, t0 + k * dt);
    step_with_parts(dt, !parts_last_only_ || k == n - 1);
  }
  time_ = t0 + dt_total;  // no drift from summing n sub-steps
  return n;
}

double ParcelSystem::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < size(); ++i) {
    if (is_rank_copy(i)) continue;
    e += 0.5 * mass[i] * (vx[i] * vx[i] + vy[i] * vy[i]) + 0.5 * inertia[i] * omega[i] * omega[i];
  }
  return e;
}

double ParcelSystem::mechanical_energy() const {
  double e = kinetic_energy();
  const ContactParams& pc = cfg_.contact;
  const ContactParams& wc = cfg_.wall_contact;
  const DemDomain& d = cfg_.domain;
  const bool listed = nbr_offset.size() == size() + 1;
  const ContactColumns columns{real_diameter.data()};
  // The active contact units add their work while touching (contact_effects/).
  with_active_contact_units(cfg_, [&](const auto&... units) {
    for (std::size_t i = 0; i < size(); ++i) {
      if (is_rank_copy(i)) continue;
      // Gravity potential of the parcel's real particles.
      e -= mass[i] * (cfg_.gravity_x * x[i] + cfg_.gravity_y * y[i]);
      for (std::int32_t k = listed ? nbr_offset[i] : 0; listed && k < nbr_offset[i + 1]; ++k) {
        const std::int32_t j = nbr_index[k];
        const double dx = x[j] + nbr_image[k] * length_x_ - x[i], dy = y[j] - y[i];
        const double overlap = radius[i] + radius[j] - std::sqrt(dx * dx + dy * dy);
        if (!(overlap > 0.0)) continue;
        // Half of the pair's spring energy on each side; the pair stands for
        // min(n_i, n_j) real contacts (compute_contacts).
        e += 0.5 * std::min(n_real[i], n_real[j]) *
             (0.5 * pc.k_n * overlap * overlap + 0.5 * pc.k_t * nbr_delta[k] * nbr_delta[k]);
        [[maybe_unused]] const double weight = 0.5 * std::min(n_real[i], n_real[j]);
        (units.pair_energy(columns, i, j, overlap, weight, e), ...);
      }
      for (int w = 0; w < kWallCount; ++w) {
        const bool on = w == 0   ? d.wall_bottom
                        : w == 1 ? d.wall_top
                        : w == 2 ? d.wall_left
                                 : d.wall_right;
        if (!on) continue;
        const double dist = w == 0   ? y[i] - d.y_min
                            : w == 1 ? d.y_max - y[i]
                            : w == 2 ? x[i] - d.x_min
                                     : d.x_max - x[i];
        const double overlap = radius[i] - dist;
        const double dt_w = wall_delta[i * kWallCount + w];
        if (!(overlap > 0.0)) continue;
        e += n_real[i] * (0.5 * wc.k_n * overlap * overlap + 0.5 * wc.k_t * dt_w * dt_w);
        (units.wall_energy(columns, i, overlap, n_real[i], e), ...);
      }
    }
  });
  return e;
}

std::size_t ParcelSystem::contact_pair_count() const {
  std::size_t n = 0;
  if (nbr_offset.size() != size() + 1) return 0;
  for (std::size_t i = 0; i < size(); ++i) {
    if (is_rank_copy(i)) continue;  // (a pair across ranks is counted on both: a diagnostic)
    for (std::int32_t k = nbr_offset[i]; k < nbr_offset[i + 1]; ++k) {
      const std::int32_t j = nbr_index[k];
      const double dx = x[j] + nbr_image[k] * length_x_ - x[i], dy = y[j] - y[i];
      const double rs = radius[i] + radius[j];
      if (dx * dx + dy * dy < rs * rs) ++n;
    }
  }
  return n / 2;
}

}  // namespace dustlift
