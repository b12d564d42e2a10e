// The vectorised flux row kernel equals the composition of the unit-tested pure functions
// (muscl_face per variable, face states from the thermodynamics, slau2_flux, face porosity),
// for both thermodynamic models and every reconstruction, its x-face path (slopes shared by a
// cell's two faces) gives the same bits as its general path; and its positivity fallback turns a
// face with a non-positive reconstructed pressure into the first-order flux.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solver/gas/flux_rows.hpp"
#include "solver/gas/slau2.hpp"

using namespace dustlift;

namespace {

struct RowData {
  std::vector<double> rho, u, v, p, alpha;
};

RowData random_row(int cells, std::mt19937& rng, double p_scale, double rho_scale) {
  std::uniform_real_distribution<double> d(0.5, 1.5), w(-1.0, 1.0);
  RowData r;
  for (int k = 0; k < cells; ++k) {
    r.rho.push_back(rho_scale * d(rng));
    r.u.push_back(300.0 * w(rng));
    r.v.push_back(100.0 * w(rng));
    r.p.push_back(p_scale * d(rng));
    r.alpha.push_back(0.4 + 0.6 * (d(rng) - 0.5));
  }
  return r;
}

StencilRows stencil(const std::vector<double>& q) { return {q.data(), q.data() + 1, q.data() + 2, q.data() + 3}; }

template <class Thermo>
FaceState face_state(const Thermo& th, double rho, double u, double v, double p) {
  const double R = th.gas_constant(), T = p / (rho * R);
  return {rho, u, v, p, th.enthalpy(T) + 0.5 * (u * u + v * v), std::sqrt(th.sound_speed_squared(T))};
}

/// The four stencil rows as separate arrays (as the y-faces see them: rows j-2 .. j+1), so
/// that the kernel takes its general path rather than the one for contiguous x-face rows.
struct SeparateRows {
  std::vector<double> m2, m1, c0, p1;
  explicit SeparateRows(const std::vector<double>& q)
      : m2(q.begin(), q.end() - 3), m1(q.begin() + 1, q.end() - 2), c0(q.begin() + 2, q.end() - 1),
        p1(q.begin() + 3, q.end()) {}
  StencilRows rows() const { return {m2.data(), m1.data(), c0.data(), p1.data()}; }
};

/// The kernel's output for a row (5 arrays of faces: mass, momenta, energy, face pressure).
template <class Thermo>
std::vector<double> kernel_row(const Thermo& th, const MusclSettings& m, const RowData& r, double nx, double ny,
                               bool separate_rows) {
  const int faces = static_cast<int>(r.rho.size()) - 3;
  const std::size_t n = static_cast<std::size_t>(faces);
  std::vector<double> scratch(8 * n), out(5 * n);
  double* s = scratch.data();
  const SeparateRows rho(r.rho), u(r.u), v(r.v), p(r.p);
  const FaceRowInput in = separate_rows ? FaceRowInput{rho.rows(), u.rows(), v.rows(), p.rows(), r.alpha.data() + 1,
                                                       r.alpha.data() + 2, faces}
                                        : FaceRowInput{stencil(r.rho), stencil(r.u), stencil(r.v), stencil(r.p),
                                                       r.alpha.data() + 1, r.alpha.data() + 2, faces};
  FaceRowScratch sc{};
  double** slots[8] = {&sc.rho_l, &sc.u_l, &sc.v_l, &sc.p_l, &sc.rho_r, &sc.u_r, &sc.v_r, &sc.p_r};
  for (std::size_t k = 0; k < 8; ++k) *slots[k] = s + k * n;
  inviscid_flux_row(th, m, in, sc,
                    {out.data(), out.data() + n, out.data() + 2 * n, out.data() + 3 * n, out.data() + 4 * n}, nx, ny);
  return out;
}

template <class Thermo>
void compare_with_pure_functions(const Thermo& th, const MusclSettings& m, const RowData& r, double nx, double ny) {
  const std::size_t n = r.rho.size() - 3;
  const std::vector<double> out = kernel_row(th, m, r, nx, ny, false);
  // The x-face path (each cell's limited slopes shared by its two faces) and the general
  // path give the same bits.
  const std::vector<double> general = kernel_row(th, m, r, nx, ny, true);
  for (std::size_t k = 0; k < out.size(); ++k) ASSERT_EQ(out[k], general[k]) << "entry " << k;
  for (std::size_t f = 0; f < n; ++f) {
    auto rec = [&](const std::vector<double>& q) { return muscl_face(q[f], q[f + 1], q[f + 2], q[f + 3], m); };
    const FacePair fr = rec(r.rho), fu = rec(r.u), fv = rec(r.v), fp = rec(r.p);
    const ConservedFlux F = slau2_flux(face_state(th, fr.left, fu.left, fv.left, fp.left),
                                       face_state(th, fr.right, fu.right, fv.right, fp.right), nx, ny);
    const double a = 0.5 * (r.alpha[f + 1] + r.alpha[f + 2]);
    const double want[4] = {a * F.mass, a * F.momentum_x, a * F.momentum_y, a * F.energy};
    // The row keeps the face pressure apart (unweighted); the full momentum flux adds a p~ n.
    const double p_face = out[4 * n + f];
    const double got[4] = {out[f], out[n + f] + a * p_face * nx, out[2 * n + f] + a * p_face * ny, out[3 * n + f]};
    for (std::size_t k = 0; k < 4; ++k) {
      const double scale = std::abs(want[k]) + a * std::abs(F.mass) * 1e3 + 1e-300;
      EXPECT_NEAR(got[k], want[k], 1e-12 * scale) << "face " << f << " component " << k;
    }
  }
}

std::vector<MusclSettings> all_settings() {
  std::vector<MusclSettings> v;
  for (Reconstruction o : {Reconstruction::FirstOrder, Reconstruction::Muscl2, Reconstruction::Muscl3}) {
    for (Limiter l : {Limiter::Minmod, Limiter::VanAlbada}) {
      SchemeConfig s;
      s.reconstruction = o;
      s.limiter = l;
      v.push_back(muscl_settings(s));
    }
  }
  return v;
}

}  // namespace

TEST(FluxRows, MatchPureFunctionsThermallyPerfectAir) {
  std::mt19937 rng(11);
  const ThermallyPerfectAir air;
  for (const MusclSettings& m : all_settings()) {
    const RowData r = random_row(37, rng, 1.5e5, 1.5);
    compare_with_pure_functions(air, m, r, 1.0, 0.0);
    compare_with_pure_functions(air, m, r, 0.0, 1.0);
  }
}

TEST(FluxRows, MatchPureFunctionsCaloricallyPerfectGas) {
  std::mt19937 rng(12);
  const CaloricallyPerfectGas gas(1.4, 287.0);
  for (const MusclSettings& m : all_settings()) {
    const RowData r = random_row(37, rng, 1.5e5, 1.5);
    compare_with_pure_functions(gas, m, r, 1.0, 0.0);
  }
}

TEST(FluxRows, NonPositiveReconstructedPressureFallsBackToFirstOrder) {
  // A steep pressure drop with an over-compressive b (beyond the TVD bound, so the face value
  // undershoots below zero) must give exactly the first-order flux at that face.
  const CaloricallyPerfectGas gas(1.4, 1.0);
  RowData r;
  r.rho = {1.0, 1.0, 1.0, 1.0, 1.0};
  r.u = {0.0, 0.0, 0.0, 0.0, 0.0};
  r.v = {0.0, 0.0, 0.0, 0.0, 0.0};
  r.p = {3.0, 2.0, 0.05, 0.04, 0.04};
  r.alpha = {1.0, 1.0, 1.0, 1.0, 1.0};
  MusclSettings wild;
  wild.order = Reconstruction::Muscl3;
  wild.limiter = Limiter::Minmod;
  wild.kappa = 1.0 / 3.0;
  wild.b = 40.0;
  // Face 1 (between cells 2 and 3 of the row): its right state extrapolates cell 2 downwards.
  const FacePair check = muscl_face(r.p[1], r.p[2], r.p[3], r.p[4], wild);
  const FacePair check0 = muscl_face(r.p[0], r.p[1], r.p[2], r.p[3], wild);
  ASSERT_TRUE(check.left <= 0.0 || check.right <= 0.0 || check0.left <= 0.0 || check0.right <= 0.0);
  const std::vector<double> out = kernel_row(gas, wild, r, 1.0, 0.0, false);
  EXPECT_EQ(out, kernel_row(gas, wild, r, 1.0, 0.0, true));
  for (int f = 0; f < 2; ++f) {
    const FacePair pf = muscl_face(r.p[f], r.p[f + 1], r.p[f + 2], r.p[f + 3], wild);
    if (pf.left > 0.0 && pf.right > 0.0) continue;
    const auto st = [&](int c) { return FaceState{1.0, 0.0, 0.0, r.p[c], 3.5 * r.p[c], std::sqrt(1.4 * r.p[c])}; };
    const ConservedFlux first = slau2_flux(st(f + 1), st(f + 2), 1.0, 0.0);
    EXPECT_NEAR(out[static_cast<std::size_t>(f)], first.mass, 1e-14);
    EXPECT_NEAR(out[2 + static_cast<std::size_t>(f)] + out[8 + static_cast<std::size_t>(f)], first.momentum_x, 1e-14);
    EXPECT_NEAR(out[6 + static_cast<std::size_t>(f)], first.energy, 1e-14);
  }
}
