// The drag closures of dense suspensions beyond the paper's: Tenneti et al. (2011) and Osnes et
// al. (2023), each against its published formula written out here and independent evaluations,
// both against Ergun's packed-bed law, and the info lines that say where a closure leaves its
// range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "insitu/parcel_fronts.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/added_mass.hpp"
#include "solver/coupling/effects/effect_list.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/laws/added_mass.hpp"
#include "solver/laws/dense_drag.hpp"
#include "solver/laws/drag.hpp"
#include "tests/unit/forcing_fixture.hpp"

using namespace dustlift;

namespace {

constexpr double kPi = std::numbers::pi;

/// Tenneti, Garg & Subramaniam (2011), eqs. as published: F = F_isol(Re_m)/(1-phi)^3 + F_phi +
/// F_phiRe with Re_m = (1-phi) Re, F_isol = 1 + 0.15 Re_m^0.687, the total force 3 pi mu d (1-phi)
/// F u_r; with the mean pressure drag taken out (times (1-phi)): 3 pi mu d (1-phi)^2 F u_r.
double tenneti_published(double re, double phi) {
  const double re_m = (1.0 - phi) * re, ag = 1.0 - phi;
  const double f_isol = 1.0 + 0.15 * std::pow(re_m, 0.687);
  const double f_phi = 5.81 * phi / (ag * ag * ag) + 0.48 * std::cbrt(phi) / (ag * ag * ag * ag);
  const double f_phi_re = phi * phi * phi * re_m * (0.95 + 0.61 * phi * phi * phi / (ag * ag));
  return ag * ag * (f_isol / (ag * ag * ag) + f_phi + f_phi_re);
}

TEST(TennetiDrag, IsThePublishedCorrelationWithoutTheMeanPressureDrag) {
  for (double phi : {0.1, 0.21, 0.4, 0.5}) {
    for (double re : {0.01, 1.0, 50.0, 300.0, 3000.0}) {
      EXPECT_NEAR(aero::tenneti_drag_factor(re, phi), tenneti_published(re, phi),
                  1e-13 * tenneti_published(re, phi))
          << "phi " << phi << ", Re " << re;
    }
  }
  // Values of the same law as OpenFOAM's and waLBerla's coefficients give it (beta / 3 pi mu d
  // at the interstitial Re): an independent evaluation, to 7 digits.
  EXPECT_NEAR(aero::tenneti_drag_factor(0.01, 0.1), 2.038283, 1e-6);
  EXPECT_NEAR(aero::tenneti_drag_factor(1.0, 0.2), 3.305876, 1e-6);
  EXPECT_NEAR(aero::tenneti_drag_factor(10.0, 0.3), 5.481220, 1e-6);
  EXPECT_NEAR(aero::tenneti_drag_factor(100.0, 0.4), 12.149786, 1e-6);
  EXPECT_NEAR(aero::tenneti_drag_factor(300.0, 0.5), 24.594409, 1e-6);
  // No particles around: Schiller-Naumann's isolated sphere.
  EXPECT_DOUBLE_EQ(aero::tenneti_drag_factor(10.0, 0.0), 1.0 + 0.15 * std::pow(10.0, 0.687));
}

/// Loth et al. (2021) for Re > 45, written out as published.
double loth_compression_published(double re, double m) {
  const double c_m =
      m < 1.5 ? 1.65 + 0.65 * std::tanh(4 * m - 3.4) : 2.18 - 0.13 * std::tanh(0.9 * m - 2.7);
  const double g_m =
      m < 0.8 ? 166 * m * m * m + 3.29 * m * m - 10.9 * m + 20 : 5 + 40 / (m * m * m);
  const double h_m = m < 1 ? 0.0239 * m * m * m + 0.212 * m * m - 0.074 * m + 1
                           : 0.93 + 1 / (3.5 + std::pow(m, 5));
  const double cd = 24 / re * (1 + 0.15 * std::pow(re, 0.687)) * h_m +
                    0.42 * c_m / (1 + 42500 / std::pow(re, 1.16 * c_m) + g_m / std::sqrt(re));
  return re * cd / 24;
}

/// Osnes et al. (2023): C_D = C_D,Loth / (1 - phi) + b3 + 24/Re (1 - phi)(b1 + b2), as Re C_D / 24.
double osnes_published(double re, double m, double phi) {
  const double ag = 1 - phi;
  const double b1 = 5.81 * phi / (ag * ag) + 0.48 * std::cbrt(phi) / (ag * ag * ag);
  const double b2 = ag * ag * phi * phi * phi * re * (0.95 + 0.61 * phi * phi * phi / (ag * ag));
  const double b3 = std::min(std::sqrt(20 * m), 1.0) *
                    (5.65 * phi - 22 * phi * phi + 23.4 * std::pow(phi, 3)) *
                    (1 + std::tanh((m - (0.65 - 0.24 * phi)) / 0.35));
  const double cd =
      24 / re * loth_compression_published(re, m) / ag + b3 + 24 / re * ag * (b1 + b2);
  return re * cd / 24;
}

TEST(OsnesDrag, IsThePublishedCorrelation) {
  const double gamma = 1.4;
  const auto kn = [&](double re, double m) { return std::sqrt(kPi * gamma / 2) * m / re; };
  for (double phi : {0.0, 0.1, 0.21, 0.4}) {
    for (double m : {0.05, 0.3, 0.74, 0.9, 1.2, 1.8}) {
      for (double re : {50.0, 300.0, 3000.0}) {
        EXPECT_NEAR(aero::osnes_drag_factor(re, m, kn(re, m), gamma, phi),
                    osnes_published(re, m, phi), 1e-12 * osnes_published(re, m, phi))
            << "phi " << phi << ", M " << m << ", Re " << re;
      }
    }
  }
  // The implementations of the authors' group (MFC, ppiclF; their b2 with (1 - phi)^2) give, at
  // points where their Loth constants are the published ones (Re C_D / 24):
  EXPECT_NEAR(aero::osnes_drag_factor(1.0, 0.1, kn(1.0, 0.1), gamma, 0.1), 1.851725, 1e-6);
  EXPECT_NEAR(aero::osnes_drag_factor(100.0, 0.3, kn(100.0, 0.3), gamma, 0.1), 6.454630, 1e-6);
  EXPECT_NEAR(aero::osnes_drag_factor(50.0, 0.5, kn(50.0, 0.5), gamma, 0.4), 11.453327, 1e-6);
  // The Mach term at the curtain's phi = 0.21 and M = 0.74 adds about 0.6 to C_D.
  const double with_mach = aero::osnes_drag_factor(3000.0, 0.74, 0.0, gamma, 0.21);
  const double without = osnes_published(3000.0, 0.74, 0.21) -
                         3000.0 / 24 * std::min(std::sqrt(20 * 0.74), 1.0) *
                             (5.65 * 0.21 - 22 * 0.21 * 0.21 + 23.4 * std::pow(0.21, 3)) *
                             (1 + std::tanh((0.74 - (0.65 - 0.24 * 0.21)) / 0.35));
  EXPECT_NEAR((with_mach - without) * 24 / 3000.0, 0.6, 0.05);
  // In the Stokes limit its volume-fraction terms are Tenneti's (both without the mean pressure
  // drag), and it is finite at zero slip.
  for (double phi : {0.1, 0.3, 0.5})
    EXPECT_NEAR(aero::osnes_drag_factor(0.0, 0.0, 0.0, gamma, phi),
                aero::tenneti_drag_factor(0.0, phi), 1e-12 * aero::tenneti_drag_factor(0.0, phi));
}

TEST(DenseDrag, ClosuresForDenseSuspensionsMeetErgunInAPackedBed) {
  // Ergun's packed-bed law (the mean pressure drag taken out), with the spread of packed-bed
  // data around it (Ergun's 150 against Carman-Kozeny's 180): within 25 % for the closures that
  // hold in a bed, from a slow to a brisk flow through the pores.
  for (double phi : {0.4, 0.5, 0.6}) {
    for (double re : {0.01, 10.0, 100.0}) {
      const double ergun = aero::ergun_drag_factor(re, phi);
      EXPECT_NEAR(aero::tenneti_drag_factor(re, phi), ergun, 0.25 * ergun) << phi << " " << re;
      EXPECT_NEAR(aero::osnes_drag_factor(re, 0.01, 0.0, 1.4, phi), ergun, 0.25 * ergun)
          << phi << " " << re;
    }
  }
  // Sangani's uncapped factor on the isolated drag is 2.6 x Ergun at the layers' 0.59: the
  // reason the info line marks it out of range there.
  aero::VolumeFractionCorrection sangani{aero::VolumeFractionCorrection::Kind::Sangani, 1.0};
  EXPECT_NEAR(aero::xi2(0.41, sangani) / aero::ergun_drag_factor(0.0, 0.59), 2.64, 0.01);
}

TEST(DenseDrag, InfoSaysWhereAClosureLeavesItsRange) {
  const auto lines = [](aero::VolumeFractionCorrection::Kind kind, FlowEnvelope e) {
    CouplingConfig c;
    c.volume_fraction.kind = kind;
    return CouplingEffects(c).validity(e);
  };
  using Kind = aero::VolumeFractionCorrection::Kind;
  const FlowEnvelope layer{0.59, 2000.0, 0.55};  // a packed dust layer under a Mach 1.44 shock
  const FlowEnvelope curtain{0.21, 3000.0, 0.74};
  EXPECT_EQ(lines(Kind::Sangani, layer).size(), 1u);
  EXPECT_NE(lines(Kind::Sangani, layer)[0].find("31.6"), std::string::npos)
      << lines(Kind::Sangani, layer)[0];
  EXPECT_TRUE(lines(Kind::Sangani, curtain).empty());
  EXPECT_EQ(lines(Kind::Osnes, layer).size(), 1u);
  EXPECT_TRUE(lines(Kind::Osnes, curtain).empty());
  // Tenneti at the curtain: Re_m and the Mach number are beyond the incompressible fit.
  EXPECT_EQ(lines(Kind::Tenneti, curtain).size(), 2u);
}

TEST(ParcelFronts, OutermostAndWeightedPercentilePoints) {
  const std::vector<double> x{0.3, 0.1, 0.5, 0.2, 0.4};
  const std::vector<double> w{1.0, 1.0, 1.0, 1.0, 96.0};
  std::vector<std::size_t> order;
  const ParcelFronts f = parcel_fronts(x, w, 0.01, order);
  EXPECT_EQ(f.x_min, 0.1);
  EXPECT_EQ(f.x_max, 0.5);
  // 1 % of 100 is reached by the first parcel; 99 % only with the heavy one at 0.4.
  EXPECT_EQ(f.x_low, 0.1);
  EXPECT_EQ(f.x_high, 0.4);
  const ParcelFronts g = parcel_fronts(x, w, 0.03, order);
  EXPECT_EQ(g.x_low, 0.3);  // 0.1, 0.2, 0.3 hold 3 % of the weight
  EXPECT_THROW(parcel_fronts(std::vector<double>{}, std::vector<double>{}, 0.01, order),
               std::invalid_argument);
}

TEST(ParcelFronts, LineOfSightEdgesWhereTheOpticalDepthCrossesTheThreshold) {
  // 1 mm bins through a 10 mm channel seen along 50 mm: one 100 um bead adds
  // (pi/4) d^2 depth / (bin height) = 3.927e-5 to its bin's optical depth.
  const LineOfSight sight{0.05, 1.0, 1e-3, 0.01};
  const double per_bead = 0.25 * kPi * 1e-8 * 0.05 / (1e-3 * 0.01);
  const std::vector<double> x{0.0002, 0.0007, 0.0015, 0.0025};
  const std::vector<double> n{25000.0, 25000.0, 20000.0, 10000.0};
  const std::vector<double> d(4, 100e-6);
  SightProfile scratch;
  const SightEdges e = line_of_sight_edges(x, n, d, sight, scratch);
  const double t0 = 50000.0 * per_bead, t1 = 20000.0 * per_bead;  // bins [0, 1) and [1, 2) mm
  ASSERT_GT(t0, 1.0);
  ASSERT_LT(t1, 1.0);
  EXPECT_NEAR(e.upstream, 0.0005 - 0.001 * (t0 - 1.0) / t0, 1e-15);
  EXPECT_NEAR(e.downstream, 0.0005 + 0.001 * (t0 - 1.0) / (t0 - t1), 1e-15);
  // The same parcels in another order give the same edges; a thinner threshold reaches further.
  const std::vector<double> xr(x.rbegin(), x.rend()), nr(n.rbegin(), n.rend());
  const SightEdges r = line_of_sight_edges(xr, nr, d, sight, scratch);
  EXPECT_EQ(r.upstream, e.upstream);
  EXPECT_EQ(r.downstream, e.downstream);
  const SightEdges thin = line_of_sight_edges(x, n, d, {0.05, 0.3, 1e-3, 0.01}, scratch);
  EXPECT_GT(thin.downstream, e.downstream);
  // Nothing dense enough: no edge.
  EXPECT_TRUE(
      std::isnan(line_of_sight_edges(x, n, d, {0.05, 100.0, 1e-3, 0.01}, scratch).upstream));
}

}  // namespace
