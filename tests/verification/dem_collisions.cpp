// DEM verification (docs/gas-solver.md): head-on pair and wall impacts against the
// spring–dashpot formulas, oblique impact (rotation sign, angular momentum), energy in a
// closed box, and bitwise thread independence.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/contact.hpp"

using namespace dustlift;

namespace {

constexpr double kD = 100e-6;
const double kMass = 980.0 * sphere_volume(kD);

/// Paper contact parameters (Table 2), no walls, a box far larger than the test.
DemConfig free_space_config() {
  DemConfig c;
  c.enabled = true;
  c.contact = ContactParams{5e4, 100.0, 1e-4, std::numeric_limits<double>::infinity()};
  c.wall_contact = c.contact;
  c.domain = DemDomain{-0.01, 0.01, -0.01, 0.01, false, false, false, false, false};
  c.courant = 0.02;
  return c;
}

ParcelInit disk(double x, double y, double vx, double vy, double omega = 0.0) {
  ParcelInit p;
  p.x = x;
  p.y = y;
  p.vx = vx;
  p.vy = vy;
  p.omega = omega;
  return p;
}

/// Overlap of parcels with ids 0 and 1 (any order in the arrays).
double pair_overlap(const ParcelSystem& s) {
  const double dx = s.x[1] - s.x[0], dy = s.y[1] - s.y[0];
  return kD - std::sqrt(dx * dx + dy * dy);
}

struct Impact {
  double restitution, duration;
};

/// Steps until the contact has ended; contact start and end times by linear interpolation
/// of the overlap (motion is linear within a step when no force acts).
template <class GapFn, class NormalSpeedFn>
Impact measure_impact(ParcelSystem& s, double dt, GapFn overlap, NormalSpeedFn approach_speed) {
  const double v_in = approach_speed(s);
  double t_start = -1.0, t_end = -1.0;
  double prev = overlap(s);
  for (int n = 0; n < 100000 && t_end < 0.0; ++n) {
    const double t0 = s.time();
    s.step(dt);
    const double now = overlap(s);
    if (t_start < 0.0 && prev <= 0.0 && now > 0.0) t_start = t0 + dt * (-prev) / (now - prev);
    if (t_start >= 0.0 && prev > 0.0 && now <= 0.0) t_end = t0 + dt * prev / (prev - now);
    prev = now;
  }
  return {-approach_speed(s) / v_in, t_end - t_start};
}

}  // namespace

TEST(DemCollision, HeadOnPairMatchesSpringDashpotRestitutionAndDuration) {
  ParcelSystem s(free_space_config());
  s.add_parcel(disk(-0.6 * kD, 0.0, 1.0, 0.0));
  s.add_parcel(disk(0.6 * kD, 0.0, -1.0, 0.0));
  const double dt = s.stable_time_step();
  // Approach speed along the line of centres (ids kept: 2 parcels never re-order here).
  auto approach = [](const ParcelSystem& p) { return p.vx[0] - p.vx[1]; };
  const Impact m = measure_impact(s, dt, pair_overlap, approach);
  const double e = contact_restitution(kMass / 2, 5e4, 1e-4);
  const double tc = contact_duration(kMass / 2, 5e4, 1e-4);
  RecordProperty("restitution", std::to_string(m.restitution));
  RecordProperty("duration", std::to_string(m.duration));
  EXPECT_NEAR(m.restitution / e - 1.0, 0.0, 0.01) << m.restitution << " vs " << e;
  EXPECT_NEAR(m.duration / tc - 1.0, 0.0, 0.01) << m.duration << " vs " << tc;
  // Momentum exchanged symmetrically: the pair's total momentum is unchanged.
  EXPECT_NEAR(s.vx[0] + s.vx[1], 0.0, 1e-12);
  EXPECT_EQ(s.omega[0], 0.0);
  std::printf("pair: e = %.6f (formula %.6f, err %.2e), t_c = %.5e s (formula %.5e, err %.2e)\n",
              m.restitution, e, m.restitution / e - 1, m.duration, tc, m.duration / tc - 1);
}

TEST(DemCollision, DiskWallImpactMatchesSpringDashpotRestitutionAndDuration) {
  DemConfig c = free_space_config();
  c.domain.wall_bottom = true;
  c.domain.y_min = 0.0;
  ParcelSystem s(c);
  s.add_parcel(disk(0.0, 0.6 * kD, 0.0, -1.0));
  const double dt = s.stable_time_step();
  auto overlap = [](const ParcelSystem& p) { return 0.5 * kD - p.y[0]; };
  auto approach = [](const ParcelSystem& p) { return -p.vy[0]; };
  const Impact m = measure_impact(s, dt, overlap, approach);
  const double e = contact_restitution(kMass, 5e4, 1e-4);
  const double tc = contact_duration(kMass, 5e4, 1e-4);
  EXPECT_NEAR(m.restitution / e - 1.0, 0.0, 0.01) << m.restitution << " vs " << e;
  EXPECT_NEAR(m.duration / tc - 1.0, 0.0, 0.01) << m.duration << " vs " << tc;
  std::printf("wall: e = %.6f (formula %.6f, err %.2e), t_c = %.5e s (formula %.5e, err %.2e)\n",
              m.restitution, e, m.restitution / e - 1, m.duration, tc, m.duration / tc - 1);
}

namespace {

/// Total z angular momentum (orbital about (px, py) + spin), per metre of depth.
double angular_momentum(const ParcelSystem& s, double px, double py) {
  double L = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    L +=
        s.mass[i] * ((s.x[i] - px) * s.vy[i] - (s.y[i] - py) * s.vx[i]) + s.inertia[i] * s.omega[i];
  }
  return L;
}

/// Disk 1 comes from the right, half a diameter above disk 0's centre line.
ParcelSystem oblique_pair(double friction, double& max_overlap, double& L0, double& L1) {
  DemConfig c = free_space_config();
  c.contact.friction = friction;
  ParcelSystem s(c);
  s.add_parcel(disk(0.0, 0.0, 0.0, 0.0));
  s.add_parcel(disk(1.2 * kD, 0.5 * kD, -1.0, 0.0));
  // About the point where they first touch (any fixed point: momentum is conserved).
  const double px = 0.5 * std::sqrt(0.75) * kD, py = 0.25 * kD;
  L0 = angular_momentum(s, px, py);
  const double dt = s.stable_time_step();
  max_overlap = 0.0;
  for (int n = 0; n < 20000; ++n) {
    s.step(dt);
    max_overlap = std::max(max_overlap, pair_overlap(s));
  }
  L1 = angular_momentum(s, px, py);
  return s;
}

}  // namespace

TEST(DemCollision, ObliqueImpactSpinsBothDisksCounterClockwise) {
  double max_overlap = 0.0, L0 = 0.0, L1 = 0.0;
  const ParcelSystem s = oblique_pair(std::numeric_limits<double>::infinity(), max_overlap, L0, L1);
  ASSERT_GT(max_overlap, 0.0);
  EXPECT_LT(pair_overlap(s), 0.0);  // separated again
  // Disk 1 slides leftwards over disk 0's upper right: friction turns 0's top to the left
  // and 1's bottom to the right, both counter-clockwise (omega_z > 0).
  EXPECT_GT(s.omega[0], 0.0);
  EXPECT_GT(s.omega[1], 0.0);
  // Linear momentum exactly, angular momentum up to the overlap lever-arm error of the
  // paper's torque r_i n x F_t (|dL|/L bounded by the maximum overlap / diameter).
  EXPECT_NEAR(s.mass[0] * s.vx[0] + s.mass[1] * s.vx[1], -s.mass[1], 1e-12 * s.mass[1]);
  EXPECT_NEAR(s.vy[0] + s.vy[1], 0.0, 1e-12);
  EXPECT_LT(std::fabs(L1 - L0), 2.0 * max_overlap / kD * std::fabs(L0));
  std::printf("oblique: omega0 = %.4e, omega1 = %.4e rad/s, |dL/L| = %.2e (bound %.2e)\n",
              s.omega[0], s.omega[1], std::fabs(L1 / L0 - 1), 2 * max_overlap / kD);
}

TEST(DemCollision, FrictionFreeObliqueImpactConservesAngularMomentumExactly) {
  double max_overlap = 0.0, L0 = 0.0, L1 = 0.0;
  const ParcelSystem s = oblique_pair(0.0, max_overlap, L0, L1);
  ASSERT_GT(max_overlap, 0.0);
  EXPECT_EQ(s.omega[0], 0.0);
  EXPECT_EQ(s.omega[1], 0.0);
  EXPECT_NEAR(L1 / L0, 1.0, 1e-10);
  // Central force: the impulse is along the line of centres at contact, so disk 0 leaves
  // at 30 degrees below the x axis (it was hit at 30 degrees above it, from the right).
  EXPECT_NEAR(std::atan2(s.vy[0], s.vx[0]), -5.0 * std::acos(-1.0) / 6.0, 2e-3);
}

namespace {

/// Random gas of parcels in a closed box with walls on all sides.
ParcelSystem closed_box(int n_side, double damping, double friction, double speed,
                        std::uint64_t seed) {
  DemConfig c = free_space_config();
  c.contact.damping = damping;
  c.contact.friction = friction;
  c.wall_contact = c.contact;
  const double L = n_side * 2.0 * kD;
  c.domain = DemDomain{0.0, L, 0.0, L, true, true, true, true, false};
  c.courant = 0.1;
  ParcelSystem s(c);
  for (int r = 0; r < n_side; ++r) {
    for (int q = 0; q < n_side; ++q) {
      const double a = 2.0 * std::acos(-1.0) * uniform_from_seed(seed);
      s.add_parcel(disk((q + 0.5) * 2.0 * kD, (r + 0.5) * 2.0 * kD, speed * std::cos(a),
                        speed * std::sin(a), 0.0));
    }
  }
  return s;
}

/// One step, returning the step-consistent energy of symplectic Euler at the start of the
/// step: kinetic energy from the product of the velocities before and after the step's
/// force, sum m v^n . v^{n+1} / 2 (+ spin alike), plus the springs' and gravity's potential
/// at x^n. For linear springs this is exactly what the scheme conserves (leapfrog's
/// invariant); the plain kinetic energy oscillates by O(omega dt) within each contact.
double step_with_energy(ParcelSystem& s, double dt, std::vector<double>& before) {
  const double potential = s.mechanical_energy() - s.kinetic_energy();
  before.resize(3 * s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    before[3 * s.id[i]] = s.vx[i];
    before[3 * s.id[i] + 1] = s.vy[i];
    before[3 * s.id[i] + 2] = s.omega[i];
  }
  s.step(dt);
  double kinetic = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double* b = &before[3 * s.id[i]];
    kinetic += 0.5 * s.mass[i] * (b[0] * s.vx[i] + b[1] * s.vy[i]) +
               0.5 * s.inertia[i] * b[2] * s.omega[i];
  }
  return kinetic + potential;
}

}  // namespace

TEST(DemEnergy, ClosedBoxWithDampingNeverGainsEnergy) {
  ParcelSystem s = closed_box(20, 1e-4, 0.5, 1.0, 7);
  const double E0 = s.mechanical_energy();
  const double dt = s.stable_time_step();
  std::vector<double> before;
  double prev = E0, worst_rise = 0.0, e = E0, e_max = 0.0, prev_window_max = E0;
  for (int w = 0; w < 20; ++w) {
    double window_max = 0.0;
    for (int n = 0; n < 1000; ++n) {
      e = step_with_energy(s, dt, before);
      worst_rise = std::max(worst_rise, (e - prev) / E0);
      window_max = std::max(window_max, e);
      prev = e;
    }
    EXPECT_LE(window_max, prev_window_max) << "window " << w;
    prev_window_max = window_max;
    e_max = std::max(e_max, window_max);
  }
  // Never above the start; single steps may rise only by the kink a contact's start or end
  // makes inside one step (about (omega dt)^2 of one contact's energy, 1/400 of E0 here).
  EXPECT_LE(e_max, E0);
  EXPECT_LT(worst_rise, 1e-5);
  EXPECT_LT(e, 0.95 * E0);  // collisions did dissipate
  std::printf(
      "closed box (damped): E_max/E0 = %.9f, largest one-step rise %.2e E0, E_end/E0 = %.4f\n",
      e_max / E0, worst_rise, e / E0);
}

TEST(DemEnergy, ClosedBoxWithoutDampingOrFrictionKeepsEnergy) {
  ParcelSystem s = closed_box(20, 0.0, 0.0, 1.0, 11);
  const double E0 = s.mechanical_energy();
  const double dt = s.stable_time_step();
  double e_max = 0.0, e_min = E0;
  for (int n = 0; n < 20000; ++n) {
    s.step(dt);
    const double e = s.mechanical_energy();
    e_max = std::max(e_max, e);
    e_min = std::min(e_min, e);
  }
  // Symplectic Euler: bounded O(omega dt) oscillation of the measured energy, no drift.
  EXPECT_LT(e_max / E0 - 1.0, 0.01);
  EXPECT_GT(e_min / E0, 0.99);
  EXPECT_NEAR(s.mechanical_energy() / E0, 1.0, 0.01);
  std::printf("closed box (elastic): E in [%.6f, %.6f] E0\n", e_min / E0, e_max / E0);
}

namespace {

/// 1,000 steps of a dense, periodic, walled, gravity-loaded mix (many rebuilds and
/// contacts), on `threads` OpenMP threads. Returns the final x, y, omega ordered by id.
std::vector<double> run_threads(int threads) {
  DemConfig c = free_space_config();
  c.contact = ContactParams{5e4, 100.0, 1e-4, 0.5};
  c.wall_contact = c.contact;
  c.domain = DemDomain{0.0, 0.04, 0.0, 0.002, true, true, false, false, true};
  c.layer = LayerConfig{0.0, 0.04, 0.0, 0.002, 0.7, 3, LayerArrangement::JitteredLattice, false};
  c.gravity_y = -9.81;
  c.courant = 0.1;
  ParcelSystem s = make_layer_system(c);
  std::uint64_t seed = 5;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double a = 2.0 * std::acos(-1.0) * uniform_from_seed(seed);
    s.vx[i] = 3.0 * std::cos(a);
    s.vy[i] = 3.0 * std::sin(a);
  }
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  const double dt = s.stable_time_step();
  for (int n = 0; n < 1000; ++n) s.step(dt);
  omp_set_num_threads(saved);
  EXPECT_GT(s.neighbour_rebuilds(), 2);
  EXPECT_GE(s.size(), kParallelMinimum);  // large enough to run threaded
  std::vector<double> out(3 * s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    out[3 * s.id[i]] = s.x[i];
    out[3 * s.id[i] + 1] = s.y[i];
    out[3 * s.id[i] + 2] = s.omega[i];
  }
  return out;
}

}  // namespace

TEST(DemDeterminism, OneAndTwoThreadsGiveBitwiseIdenticalStates) {
  const std::vector<double> a = run_threads(1);
  const std::vector<double> b = run_threads(2);
  ASSERT_EQ(a.size(), b.size());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k) differing += (a[k] != b[k]);
  EXPECT_EQ(differing, 0u);
}
