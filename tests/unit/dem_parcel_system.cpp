// ParcelSystem mechanics: sub-stepping API, the gas forcing (exact discrete solutions), the
// contact history surviving neighbour rebuilds and re-sorting, and the contact pass's two ways
// through the neighbour list giving the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/dem/parcel_system.hpp"
#include "tests/unit/forcing_fixture.hpp"

using namespace dustlift;

namespace {

DemConfig open_space() {
  DemConfig c;
  c.enabled = true;
  c.domain = DemDomain{-0.01, 0.01, -0.01, 0.01, false, false, false, false, false};
  return c;
}

}  // namespace

TEST(DemParcelSystem, AdvanceSubCyclesWithEquation18AndCallsTheHookEachSubStep) {
  ParcelSystem s(open_space());
  ParcelInit p;
  p.n_real = 15000.0;
  s.add_parcel(p);
  const double m = 980.0 * sphere_volume(100e-6);
  // Eq. (18): nu sqrt(m / max k) with the real-particle mass.
  EXPECT_NEAR(s.stable_time_step(), 0.1 * std::sqrt(m / 5e4), 1e-20);
  EXPECT_NEAR(s.stable_time_step(), 1.013e-8, 0.001e-8);
  CouplingConfig c = forcing_fixture::no_effects();
  c.pressure_force = c.heat_transfer = true;
  forcing_fixture::Forcing f(s, c);
  const double F = 1e-9;  // N per real particle (the pressure-force columns)
  forcing_fixture::column(s, "pressure_fx") = F;
  forcing_fixture::column(s, "pressure_fy") = -2 * F;
  const double H = 1e-9, Tg = 1300.0;  // W/K and K: Q = H (T_g - T)
  forcing_fixture::column(s, "heat_coefficient") = H;
  forcing_fixture::column(s, "gas_temperature") = Tg;
  int calls = 0;
  const double dt_cfd = 4.1e-7;  // a paper-like CFD step
  const int n = s.advance(dt_cfd, [&](ParcelSystem&, double) { ++calls; });
  EXPECT_EQ(n, static_cast<int>(std::ceil(dt_cfd / s.stable_time_step())));
  EXPECT_EQ(calls, n);
  EXPECT_DOUBLE_EQ(s.time(), dt_cfd);
  // Constant force: symplectic Euler gives the exact velocity F t / m_real.
  EXPECT_NEAR(s.vx[0], F / m * dt_cfd, 1e-12 * F / m * dt_cfd);
  EXPECT_NEAR(s.vy[0], -2 * F / m * dt_cfd, 1e-12 * F / m * dt_cfd);
  // Eq. (7) with explicit sub-steps: T_n = T_g - (T_g - T_0) (1 - H dt / (m c))^n exactly.
  const double dt = dt_cfd / n, r = 1.0 - H * dt / (m * 1200.0);
  const double T_n = Tg - (Tg - 300.0) * std::pow(r, n);
  EXPECT_NEAR(s.temperature[0], T_n, 1e-12 * 300.0);
  // The heat taken from the gas is what the particle gained; the pressure force is not
  // exchanged (the gas feels it through alpha grad p), so no impulse and no work.
  EXPECT_NEAR(forcing_fixture::column(s, "heat"), m * 1200.0 * (s.temperature[0] - 300.0),
              1e-9 * m * 1200.0);
  EXPECT_EQ(forcing_fixture::column(s, "impulse_x"), 0.0);
  EXPECT_EQ(forcing_fixture::column(s, "work"), 0.0);
  EXPECT_NEAR(forcing_fixture::column(s, "heat_rate"), H * (Tg - T_n) / r, 1e-9 * H * Tg)
      << "the last sub-step's Q";
}

TEST(DemParcelSystem, DragForcingRelaxesTheSlipAndSumsTheExchangeExactly) {
  // F = K (u_g - v): v_n = u_g (1 - (1 - K dt / m)^n); the impulse taken from the gas is the
  // momentum m v_n and its work, with the symplectic-Euler mean velocity, exactly m v_n^2 / 2.
  ParcelSystem s(open_space());
  s.add_parcel(ParcelInit{});
  const double m = 980.0 * sphere_volume(100e-6);
  CouplingConfig c = forcing_fixture::no_effects();
  c.drag = true;
  forcing_fixture::Forcing f(s, c);
  const double ug = 200.0, vg = -50.0, K = 4e-7;
  forcing_fixture::column(s, "gas_u") = ug;
  forcing_fixture::column(s, "gas_v") = vg;
  forcing_fixture::column(s, "drag_coefficient") = K;
  const double dt_cfd = 1e-6;
  const int n = s.advance(dt_cfd);
  const double r = 1.0 - K * (dt_cfd / n) / m;
  EXPECT_NEAR(s.vx[0], ug * (1.0 - std::pow(r, n)), 1e-10 * ug);
  EXPECT_NEAR(s.vy[0], vg * (1.0 - std::pow(r, n)), 1e-10 * ug);
  EXPECT_NEAR(forcing_fixture::column(s, "impulse_x"), m * s.vx[0], 1e-12 * m * ug);
  EXPECT_NEAR(forcing_fixture::column(s, "impulse_y"), m * s.vy[0], 1e-12 * m * ug);
  const double ke = 0.5 * m * (s.vx[0] * s.vx[0] + s.vy[0] * s.vy[0]);
  EXPECT_NEAR(forcing_fixture::column(s, "work"), ke, 1e-10 * ke);
  EXPECT_NEAR(forcing_fixture::column(s, "drag_fx"), K * (ug - s.vx[0]) / r, 1e-9 * K * ug)
      << "the last sub-step's drag";
}

TEST(DemParcelSystem, GravityAcceleratesEveryParcelAlike) {
  DemConfig c = open_space();
  c.gravity_y = -9.81;
  ParcelSystem s(c);
  ParcelInit p;
  s.add_parcel(p);
  p.x = 0.005;
  p.n_real = 7.0;
  s.add_parcel(p);
  const double dt = s.stable_time_step();
  for (int k = 0; k < 100; ++k) s.step(dt);
  EXPECT_NEAR(s.vy[0], -9.81 * 100 * dt, 1e-12);
  EXPECT_EQ(s.vy[0], s.vy[1]);
}

TEST(DemParcelSystem, ContactHistorySurvivesRebuildsAndResorting) {
  // A dense, agitated pack in a closed box (walls, no periodic wrap, so positions compare
  // bit for bit): the run that rebuilds the list (and re-sorts the parcels) every step must
  // match the one that rebuilds rarely, which needs every pair's and every wall's
  // tangential elongation carried over by id.
  auto run = [](bool rebuild_every_step) {
    DemConfig c = open_space();
    c.contact = ContactParams{5e4, 100.0, 1e-4, 0.5};
    c.wall_contact = c.contact;
    c.domain = DemDomain{0.0, 0.003, 0.0, 0.002, true, true, true, true, false};
    c.layer = LayerConfig{0.0, 0.003, 0.0, 0.002, 0.7, 8, LayerArrangement::JitteredLattice, false};
    ParcelSystem s = make_layer_system(c);
    std::uint64_t seed = 99;
    for (std::size_t i = 0; i < s.size(); ++i) {
      s.vx[i] = 4.0 * (uniform_from_seed(seed) - 0.5);
      s.vy[i] = 4.0 * (uniform_from_seed(seed) - 0.5);
    }
    const double dt = s.stable_time_step();
    for (int n = 0; n < 3000; ++n) {
      if (rebuild_every_step) s.invalidate_neighbours();
      s.step(dt);
    }
    std::vector<double> out(3 * s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      out[3 * s.id[i]] = s.x[i];
      out[3 * s.id[i] + 1] = s.y[i];
      out[3 * s.id[i] + 2] = s.omega[i];
    }
    return std::make_pair(out, s.neighbour_rebuilds());
  };
  const auto [rare, n_rare] = run(false);
  const auto [every, n_every] = run(true);
  EXPECT_LT(n_rare, 100);
  EXPECT_EQ(n_every, 3000);
  ASSERT_EQ(rare.size(), every.size());
  std::size_t differing = 0;
  double max_omega = 0.0;
  for (std::size_t k = 0; k < rare.size(); ++k) {
    differing += (rare[k] != every[k]);
    if (k % 3 == 2) max_omega = std::max(max_omega, std::fabs(rare[k]));
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(max_omega, 1.0);  // the tangential contacts did act
}

TEST(DemParcelSystem, ContactPassGivesTheSameBitsSlotBySlotAndParcelByParcel) {
  // An agitated periodic layer between walls, three chunks of the contact pass: a dense
  // quarter at 4 m/s (most listed pairs touch) beside a loose rest at 0.5 m/s (few do), parcels
  // of one and two real particles (the pair rule between counts) and a restitution (each
  // pair's dashpot from its reduced mass). Walking the list slot by slot, parcel by parcel, or
  // choosing per chunk must give the same forces, springs and paths, bit for bit.
  using Traversal = ParcelSystem::ContactTraversal;
  auto run = [](Traversal traversal, std::size_t& touching_steps) {
    DemConfig c = open_space();
    const double d = 100e-6, k_n = 5e4;
    c.particle_diameter = c.parcel_diameter = d;
    c.density = 980.0;
    const double m = 980.0 * sphere_volume(d);
    c.contact = ContactParams{k_n, 2.0 / 7.0 * k_n, damping_for_restitution(m / 2, k_n, 0.9), 0.5};
    c.contact.restitution = 0.9;
    c.wall_contact = c.contact;
    c.domain = DemDomain{0.0, 0.02, 0.0, 0.002, true, true, false, false, true};
    c.layer =
        LayerConfig{0.0, 0.02, 0.0, 0.002, 0.589, 1, LayerArrangement::JitteredLattice, false};
    c.gravity_y = -9.81;
    ParcelSystem s = make_layer_system(c);
    s.set_contact_traversal(traversal);
    std::uint64_t seed = 7;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double speed = s.x[i] < 0.005 ? 4.0 : 0.5;
      const double a = 6.283185307179586 * uniform_from_seed(seed);
      s.vx[i] = speed * std::cos(a);
      s.vy[i] = speed * std::sin(a);
      if (s.id[i] % 3 == 0) s.n_real[i] = 2.0;
    }
    const double dt = s.stable_time_step();
    touching_steps = 0;
    for (int n = 0; n < 2000; ++n) {
      s.step(dt);
      touching_steps += s.contact_pair_count() > 0 ? 1 : 0;
    }
    std::vector<double> out(5 * s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto at = 5 * static_cast<std::size_t>(s.id[i]);
      out[at] = s.x[i];
      out[at + 1] = s.y[i];
      out[at + 2] = s.vx[i];
      out[at + 3] = s.vy[i];
      out[at + 4] = s.omega[i];
    }
    return std::make_pair(out, s.size());
  };
  std::size_t touching_by_parcel = 0, touching_by_slot = 0, touching_adaptive = 0;
  const auto [by_parcel, n] = run(Traversal::ByParcel, touching_by_parcel);
  const auto [by_slot, n_slot] = run(Traversal::BySlot, touching_by_slot);
  const auto [adaptive, n_adaptive] = run(Traversal::Adaptive, touching_adaptive);
  ASSERT_GT(n, 2u * 1024u);              // at least three chunks
  EXPECT_GT(touching_by_parcel, 1900u);  // pairs touched in nearly every step
  std::size_t slot_differs = 0, adaptive_differs = 0;
  double max_omega = 0.0;
  for (std::size_t k = 0; k < by_parcel.size(); ++k) {
    slot_differs += by_parcel[k] != by_slot[k];
    adaptive_differs += by_parcel[k] != adaptive[k];
    if (k % 5 == 4) max_omega = std::max(max_omega, std::fabs(by_parcel[k]));
  }
  EXPECT_EQ(slot_differs, 0u);
  EXPECT_EQ(adaptive_differs, 0u);
  EXPECT_GT(max_omega, 1.0);  // the tangential contacts did act
}

TEST(DemParcelSystem, ARebuildKeepsTheListsOfUnmovedNeighbourhoodsAndListsTheSame) {
  // A loose periodic layer at rest (no gravity, no parcel touching: no parcel moves) beside a
  // stirred quarter whose parcels run into it: every rebuild's list must be the one a full
  // search gives, slot by slot with its history, while most resting parcels keep theirs.
  auto make = [](bool keep) {
    DemConfig c = open_space();
    const double d = 100e-6, k_n = 5e4;
    c.particle_diameter = c.parcel_diameter = d;
    c.density = 980.0;
    c.contact = ContactParams{k_n, 2.0 / 7.0 * k_n, 1e-4, 0.5};
    c.wall_contact = c.contact;
    c.domain = DemDomain{0.0, 0.02, 0.0, 0.002, true, true, false, false, true};
    c.layer = LayerConfig{0.0, 0.02, 0.0, 0.002, 0.3, 1, LayerArrangement::JitteredLattice, false};
    ParcelSystem s = make_layer_system(c);
    s.set_keep_unchanged_lists(keep);
    std::uint64_t seed = 11;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double a = 6.283185307179586 * uniform_from_seed(seed);
      const double speed = s.x[i] < 0.005 ? 4.0 : 0.0;
      s.vx[i] = speed * std::cos(a);
      s.vy[i] = speed * std::sin(a);
    }
    return s;
  };
  ParcelSystem kept = make(true), searched = make(false);
  const double dt = kept.stable_time_step();
  std::size_t differing_lists = 0;
  for (int n = 0; n < 4000; ++n) {
    kept.step(dt);
    searched.step(dt);
    differing_lists += kept.nbr_offset != searched.nbr_offset ||
                       kept.nbr_index != searched.nbr_index ||
                       kept.nbr_image != searched.nbr_image || kept.nbr_delta != searched.nbr_delta;
  }
  EXPECT_EQ(differing_lists, 0u);
  EXPECT_GT(kept.neighbour_rebuilds(), 16);  // re-sorting ones and keeping ones
  EXPECT_EQ(searched.kept_lists(), 0);
  // Most of the layer rested through most rebuilds.
  const double listed =
      static_cast<double>(kept.neighbour_rebuilds()) * static_cast<double>(kept.size());
  EXPECT_GT(static_cast<double>(kept.kept_lists()) / listed, 0.3);
  std::size_t differing_paths = 0, moved = 0;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    differing_paths += kept.x[i] != searched.x[i] || kept.y[i] != searched.y[i] ||
                       kept.omega[i] != searched.omega[i];
    moved += kept.vx[i] != 0.0 || kept.vy[i] != 0.0;
  }
  EXPECT_EQ(differing_paths, 0u);
  // The stirred quarter hit resting parcels (lists around them had to be searched again).
  EXPECT_GT(moved, kept.size() / 4);
}
