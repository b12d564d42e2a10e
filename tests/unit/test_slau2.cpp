// SLAU2 flux: consistency, stationary contacts, mirror symmetry, supersonic pressure upwinding.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/gas/slau2.hpp"

using namespace dustlift;

namespace {

FaceState make_state(double rho, double u, double v, double p, double gamma = 1.4) {
  const double c = std::sqrt(gamma * p / rho);
  const double H = gamma / (gamma - 1.0) * p / rho + 0.5 * (u * u + v * v);
  return {rho, u, v, p, H, c};
}

void expect_flux_near(const ConservedFlux& a, const ConservedFlux& b, double scale) {
  EXPECT_NEAR(a.mass, b.mass, 1e-13 * scale);
  EXPECT_NEAR(a.momentum_x, b.momentum_x, 1e-13 * scale);
  EXPECT_NEAR(a.momentum_y, b.momentum_y, 1e-13 * scale);
  EXPECT_NEAR(a.energy, b.energy, 1e-13 * scale);
}

const std::vector<FaceState> kStates = {
    make_state(1.0, 0.0, 0.0, 1.0),        make_state(1.2, 0.3, -0.2, 0.8),
    make_state(0.5, -0.9, 0.4, 2.0),       make_state(1.17, 650.0, 10.0, 1.01e5),
    make_state(2.05, -216.0, 30.0, 2.27e5), make_state(0.1, 5.0, -3.0, 0.2)};
const std::vector<std::pair<double, double>> kNormals = {{1, 0}, {0, 1}, {-1, 0}, {0.6, 0.8}};

}  // namespace

TEST(Slau2, ConsistentWithPhysicalFlux) {
  for (const FaceState& s : kStates) {
    for (auto [nx, ny] : kNormals) {
      const ConservedFlux exact = euler_flux(s, nx, ny);
      const double scale = s.p + s.rho * (s.u * s.u + s.v * s.v) + s.rho * s.H * (std::abs(s.u) + std::abs(s.v) + s.c);
      expect_flux_near(slau2_flux(s, s, nx, ny), exact, scale);
    }
  }
}

TEST(Slau2, StationaryContactHasNoMassFluxAndExactPressure) {
  // Different densities and tangential velocities, zero normal velocity, equal pressure.
  const FaceState L = make_state(1.0, 0.0, 0.7, 1.0);
  const FaceState R = make_state(0.125, 0.0, -0.3, 1.0);
  const ConservedFlux f = slau2_flux(L, R, 1.0, 0.0);
  EXPECT_EQ(f.mass, 0.0);
  EXPECT_EQ(f.momentum_x, 1.0);
  EXPECT_EQ(f.momentum_y, 0.0);
  EXPECT_EQ(f.energy, 0.0);
}

TEST(Slau2, MirrorSymmetry) {
  // F(L, R, n) = -F(R, L, -n): the same face seen from the other side.
  for (const FaceState& L : kStates) {
    for (const FaceState& R : kStates) {
      if (L.p / R.p > 10 || R.p / L.p > 10) continue;  // keep to states of one scale
      for (auto [nx, ny] : kNormals) {
        const ConservedFlux a = slau2_flux(L, R, nx, ny);
        const ConservedFlux b = slau2_flux(R, L, -nx, -ny);
        const double scale = std::abs(a.mass) + std::abs(a.momentum_x) + std::abs(a.momentum_y) + std::abs(a.energy) + L.p;
        EXPECT_NEAR(a.mass, -b.mass, 1e-13 * scale);
        EXPECT_NEAR(a.momentum_x, -b.momentum_x, 1e-13 * scale);
        EXPECT_NEAR(a.momentum_y, -b.momentum_y, 1e-13 * scale);
        EXPECT_NEAR(a.energy, -b.energy, 1e-13 * scale);
      }
    }
  }
}

TEST(Slau2, SupersonicPressureIsUpwind) {
  const FaceState L = make_state(1.0, 3.0, 0.0, 1.0);
  const FaceState R = make_state(0.8, 2.9, 0.0, 0.7);
  const ConservedFlux f = slau2_flux(L, R, 1.0, 0.0);
  EXPECT_GT(f.mass, 0.0);
  EXPECT_NEAR(f.momentum_x - f.mass * L.u, L.p, 1e-14);  // p~ = p_L, convected state Psi_L
  EXPECT_NEAR(f.energy, f.mass * L.H, 1e-13 * f.energy);
}

TEST(Slau2, WallMirrorGivesZeroMassFlux) {
  // A state against its mirror image (ghost cell of a slip wall): no mass or energy through it.
  for (double un : {-0.5, 0.0, 0.4, 1.7}) {
    const FaceState L = make_state(1.3, un, 0.2, 0.9);
    const FaceState R = make_state(1.3, -un, 0.2, 0.9);
    const ConservedFlux f = slau2_flux(L, R, 1.0, 0.0);
    // Zero up to round-off (the compiler may fuse multiply-adds asymmetrically).
    EXPECT_NEAR(f.mass, 0.0, 1e-15 * L.rho * L.c) << un;
    EXPECT_NEAR(f.energy, 0.0, 1e-15 * L.rho * L.c * L.H) << un;
    EXPECT_GT(f.momentum_x, 0.0);
  }
}
