// What counts as "at rest" for the skipping, of cells (rest_ranges.hpp) and of parcels
// (resting_parcels.hpp): exact by default, within run.rest_tolerance when it is set (the scene
// key's checks: test_scene.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solver/coupling/resting_parcels.hpp"
#include "solver/gas/rest_ranges.hpp"

using namespace dustlift;

namespace {

constexpr double kP = 101.0e3, kT = 300.0, kRho = 1.1729;

bool cell_rests(double u, double v, double p, double T, const RestReference& ref) {
  const RowView row{&u, &v, &p, &T, 1};
  return rests_at(row, 0, ref);
}

ParcelMotion still_parcel() {
  // A 100 um particle of 980 kg/m^3 (per metre of depth as the DEM stores it: the values only
  // set the scale of the force and torque tolerances).
  return {0.0, 0.0, 0.0, 50e-6, 0.0, 0.0, 0.0, 7.7e-9, 9.6e-18};
}

}  // namespace

TEST(RestTolerance, ZeroToleranceIsExactEquality) {
  const RestReference ref = rest_reference(0.0, 0.0, kP, kT, kRho, 0.0);
  EXPECT_TRUE(ref.valid);
  EXPECT_TRUE(cell_rests(0.0, -0.0, kP, kT, ref));
  EXPECT_FALSE(cell_rests(0.0, 0.0, std::nextafter(kP, 2 * kP), kT, ref));  // one ulp of p
  EXPECT_FALSE(cell_rests(0.0, 0.0, kP, std::nextafter(kT, 0.0), ref));
  EXPECT_FALSE(cell_rests(std::numeric_limits<double>::denorm_min(), 0.0, kP, kT, ref));
  EXPECT_FALSE(cell_rests(0.0, 0.0, std::nan(""), kT, ref));
  // A reference cell that moves at all is no reference.
  EXPECT_FALSE(rest_reference(1e-300, 0.0, kP, kT, kRho, 0.0).valid);
}

TEST(RestTolerance, RelativeToleranceWidensEveryVariable) {
  const double tol = 1e-10;
  const RestReference ref = rest_reference(0.0, 0.0, kP, kT, kRho, tol);
  const double du = tol * std::sqrt(kP / kRho);  // ~2.9e-8 m/s
  EXPECT_NEAR(ref.du, du, 1e-22);
  EXPECT_DOUBLE_EQ(ref.dp, tol * kP);
  EXPECT_DOUBLE_EQ(ref.dT, tol * kT);
  // Rounding noise of the size that runs ahead of a shock rests ...
  EXPECT_TRUE(cell_rests(1e-14, -3e-15, kP * (1 + 4e-16), kT * (1 - 2e-16), ref));
  EXPECT_TRUE(cell_rests(0.5 * du, -0.5 * du, kP * (1 + 0.5 * tol), kT * (1 - 0.5 * tol), ref));
  // ... a disturbance twice the tolerance in any one variable does not.
  EXPECT_FALSE(cell_rests(2 * du, 0.0, kP, kT, ref));
  EXPECT_FALSE(cell_rests(0.0, -2 * du, kP, kT, ref));
  EXPECT_FALSE(cell_rests(0.0, 0.0, kP * (1 + 2 * tol), kT, ref));
  EXPECT_FALSE(cell_rests(0.0, 0.0, kP, kT * (1 - 2 * tol), ref));
  // The reference itself may carry noise below the tolerance, not more.
  EXPECT_TRUE(rest_reference(0.5 * du, 0.0, kP, kT, kRho, tol).valid);
  EXPECT_FALSE(rest_reference(0.0, 2 * du, kP, kT, kRho, tol).valid);
}

TEST(RestTolerance, ParcelStillExactlyWithoutTolerance) {
  const double dt = 1e-7;
  EXPECT_TRUE(parcel_still(still_parcel(), 0.0, dt));
  // The smallest force there is must count: no product in the test may underflow to zero.
  ParcelMotion m = still_parcel();
  m.fy = std::numeric_limits<double>::denorm_min();
  EXPECT_FALSE(parcel_still(m, 0.0, dt));
  m = still_parcel();
  m.torque = -std::numeric_limits<double>::denorm_min();
  EXPECT_FALSE(parcel_still(m, 0.0, dt));
  m = still_parcel();
  m.omega = 1e-300;
  EXPECT_FALSE(parcel_still(m, 0.0, dt));
}

TEST(RestTolerance, ParcelStillWithinTolerance) {
  const double dt = 1e-7, du = 3e-8;
  const ParcelMotion base = still_parcel();
  ParcelMotion m = base;
  m.vx = 0.9 * du;
  m.vy = -0.9 * du;
  m.omega = 0.9 * du / base.radius;
  // Forces that would add 0.9 du within dt.
  m.fx = 0.9 * du * base.mass_real / dt;
  m.torque = -0.9 * du * base.inertia_real / (base.radius * dt);
  EXPECT_TRUE(parcel_still(m, du, dt));
  for (int k = 0; k < 5; ++k) {
    ParcelMotion over = base;
    switch (k) {
      case 0:
        over.vx = 1.1 * du;
        break;
      case 1:
        over.vy = -1.1 * du;
        break;
      case 2:
        over.omega = 1.1 * du / base.radius;
        break;
      case 3:
        over.fy = 1.1 * du * base.mass_real / dt;
        break;
      default:
        over.torque = 1.1 * du * base.inertia_real / (base.radius * dt);
        break;
    }
    EXPECT_FALSE(parcel_still(over, du, dt)) << "component " << k;
  }
}
