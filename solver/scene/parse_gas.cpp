// [gas], [boundary], [initial]: the gas solver's sections.
#include <fmt/format.h>

#include <stdexcept>

#include "solver/gas/shock_relations.hpp"
#include "solver/gas/thermo.hpp"
#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {

namespace {
/// The temperatures the NASA-7 fits of air cover (thermo.hpp: 200-1000 K and 1000-6000 K).
constexpr double kFitMin = 200.0, kFitMax = 6000.0;
}  // namespace

void check_gas_temperature(TableReader& t, std::string_view key, double T,
                           const ThermoConfig& thermo) {
  if (thermo.model != ThermoModel::ThermallyPerfect) return;
  if (!(T >= kFitMin && T <= kFitMax)) {
    t.fail(key,
           fmt::format(
               "T = {:.6g} K lies outside the NASA-7 fits of thermally perfect air ({:g}-{:g} K); "
               "use gas.thermo = \"calorically_perfect\" for such a gas",
               T, kFitMin, kFitMax));
  }
}

PrimitiveState parse_state(TableReader t, const ThermoConfig& thermo) {
  t.expect_keys({"p", "rho", "T", "u", "v"});
  PrimitiveState s;
  s.p = t.required_number("p", Range::positive());
  check_plausible_pressure(t, "p", s.p);
  s.u = t.number("u", 0.0);
  s.v = t.number("v", 0.0);
  const bool has_rho = t.has("rho"), has_T = t.has("T");
  if (has_rho == has_T) t.fail(has_rho ? "T" : "rho", "give exactly one of rho or T");
  if (has_rho) {
    s.rho = t.required_number("rho", Range::positive());
    check_gas_temperature(t, "rho", s.p / (s.rho * thermo.gas_constant), thermo);
  } else {
    // p = rho R T (eq. 4) holds for both thermodynamic models.
    const double T = t.required_number("T", Range::positive());
    check_plausible_temperature(t, "T", T);
    check_gas_temperature(t, "T", T, thermo);
    s.rho = s.p / (thermo.gas_constant * T);
    s.T = T;  // kept exactly: p / (rho R) would differ from it in the last bit
  }
  t.finish();
  return s;
}

void parse_gas(TableReader t, GasConfig& gas) {
  t.expect_keys({"thermo", "gamma", "gas_constant", "transport", "scheme", "gravity"});
  const auto thermo =
      t.choice("thermo", "thermally_perfect", {"thermally_perfect", "calorically_perfect"});
  gas.thermo.model = thermo == "thermally_perfect" ? ThermoModel::ThermallyPerfect
                                                   : ThermoModel::CaloricallyPerfect;
  // gamma is read (and so written into the resolved scene) only where it is used, so the
  // resolved scene of thermally perfect air parses back.
  if (gas.thermo.model == ThermoModel::ThermallyPerfect) {
    if (t.has("gamma")) {
      t.fail("gamma",
             "only used with thermo = \"calorically_perfect\" (thermally perfect air takes cp(T) "
             "from NASA polynomials)");
    }
  } else {
    gas.thermo.gamma = t.number("gamma", 1.4, Range::open(1.0, 5.0 / 3.0 + 1e-12));
  }
  gas.thermo.gas_constant = t.number("gas_constant", 288.190, Range::positive());
  // Gravity on the gas, a vector like particles.gravity (off by default: the paper's eqs.
  // 1-3 have none).
  const std::vector<double> g = t.number_list("gravity", {0.0, 0.0});
  if (g.size() != 2) t.fail("gravity", "a gravity vector has two components, [g_x, g_y] in m/s^2");
  gas.gravity_x = g[0];
  gas.gravity_y = g[1];

  TableReader tr = t.table("transport");
  tr.expect_keys(
      {"model", "viscosity", "prandtl", "sutherland_mu_ref", "sutherland_t_ref", "sutherland_s"});
  const auto model =
      tr.choice("model", "gordon_wilke", {"inviscid", "constant", "sutherland", "gordon_wilke"});
  gas.transport.model = model == "inviscid"     ? TransportModel::Inviscid
                        : model == "constant"   ? TransportModel::Constant
                        : model == "sutherland" ? TransportModel::Sutherland
                                                : TransportModel::GordonWilke;
  gas.transport.viscosity = tr.number("viscosity", gas.transport.viscosity, Range::positive());
  gas.transport.prandtl = tr.number("prandtl", gas.transport.prandtl, Range::positive());
  gas.transport.sutherland_mu_ref =
      tr.number("sutherland_mu_ref", gas.transport.sutherland_mu_ref, Range::positive());
  gas.transport.sutherland_t_ref =
      tr.number("sutherland_t_ref", gas.transport.sutherland_t_ref, Range::positive());
  gas.transport.sutherland_s =
      tr.number("sutherland_s", gas.transport.sutherland_s, Range::non_negative());
  tr.finish();

  TableReader sc = t.table("scheme");
  sc.expect_keys({"reconstruction", "limiter", "minmod_b", "cfl"});
  const auto rec = sc.choice("reconstruction", "muscl3", {"first_order", "muscl2", "muscl3"});
  gas.scheme.reconstruction = rec == "first_order" ? Reconstruction::FirstOrder
                              : rec == "muscl2"    ? Reconstruction::Muscl2
                                                   : Reconstruction::Muscl3;
  const auto lim = sc.choice("limiter", "minmod", {"minmod", "van_albada"});
  gas.scheme.limiter = lim == "minmod" ? Limiter::Minmod : Limiter::VanAlbada;
  gas.scheme.minmod_b = sc.number("minmod_b", gas.scheme.minmod_b, Range::closed(1.0, 4.0));
  gas.scheme.cfl = sc.number("cfl", gas.scheme.cfl, Range::open_closed(0.0, 1.0));
  if (gas.scheme.cfl < kMinCourant) {
    sc.fail(
        "cfl",
        fmt::format(
            "{:g} is below {:g}: the run would take more than {:g} times the steps of a usual CFL "
            "(0.5), which is no stability gain",
            gas.scheme.cfl, kMinCourant, 0.5 / kMinCourant));
  }
  sc.finish();
  t.finish();
}

static BoundaryKind boundary_kind(TableReader& t, std::string_view side, const char* fallback) {
  const auto k =
      t.choice(side, fallback, {"slip_wall", "no_slip_wall", "inflow", "outflow", "periodic"});
  if (k == "slip_wall") return BoundaryKind::SlipWall;
  if (k == "no_slip_wall") return BoundaryKind::NoSlipWall;
  if (k == "inflow") return BoundaryKind::Inflow;
  if (k == "outflow") return BoundaryKind::Outflow;
  return BoundaryKind::Periodic;
}

void parse_boundary(TableReader t, BoundaryConfig& b, const ThermoConfig& thermo) {
  t.expect_keys({"left", "right", "bottom", "top", "inflow"});
  b.left = boundary_kind(t, "left", "outflow");
  b.right = boundary_kind(t, "right", "outflow");
  b.bottom = boundary_kind(t, "bottom", "slip_wall");
  b.top = boundary_kind(t, "top", "slip_wall");
  if ((b.left == BoundaryKind::Periodic) != (b.right == BoundaryKind::Periodic)) {
    t.fail(b.left == BoundaryKind::Periodic ? "right" : "left",
           "periodic boundaries come in pairs (left and right)");
  }
  if ((b.bottom == BoundaryKind::Periodic) != (b.top == BoundaryKind::Periodic)) {
    t.fail(b.bottom == BoundaryKind::Periodic ? "top" : "bottom",
           "periodic boundaries come in pairs (bottom and top)");
  }
  if (t.has("inflow")) {
    b.inflow = parse_state(t.table("inflow"), thermo);
    b.inflow_given = true;
  }
  t.finish();
}

void parse_initial(TableReader t, InitialCondition& ic, const ThermoConfig& thermo,
                   const GridConfig& grid) {
  t.expect_keys({"kind", "state", "left", "right", "position", "axis", "mach"});
  const auto kind = t.choice("kind", "uniform", {"uniform", "riemann", "shock"});
  if (kind == "uniform") {
    ic.kind = InitialCondition::Kind::Uniform;
    ic.state = parse_state(t.table("state", true), thermo);
    t.finish();
    return;
  }
  if (kind == "riemann") {
    ic.kind = InitialCondition::Kind::Riemann;
    ic.left = parse_state(t.table("left", true), thermo);
    ic.right = parse_state(t.table("right", true), thermo);
  } else {
    ic.kind = InitialCondition::Kind::Shock;
    ic.state = parse_state(t.table("state", true), thermo);
    ic.mach = t.required_number("mach", Range::open(1.0, 50.0));
  }
  ic.position = t.required_number("position");
  ic.axis = t.choice("axis", "x", {"x", "y"})[0];
  const AxisSpec& a = ic.axis == 'x' ? grid.x : grid.y;
  if (ic.position <= a.start || ic.position >= a.end) {
    t.fail("position", fmt::format("{:.9g} lies outside the grid along {} ({:.9g} to {:.9g} m)",
                                   ic.position, ic.axis, a.start, a.end));
  }
  if (ic.kind == InitialCondition::Kind::Shock) {
    // The post-shock state must exist and stay within what the gas model covers.
    try {
      const ShockJump jump = normal_shock(ic.state, ic.mach, thermo, ic.axis);
      if (thermo.model == ThermoModel::ThermallyPerfect && jump.post_temperature > kFitMax) {
        t.fail("mach",
               fmt::format("the post-shock temperature {:.6g} K lies beyond the NASA-7 fits of air "
                           "(up to {:g} K)",
                           jump.post_temperature, kFitMax));
      }
    } catch (const std::invalid_argument& e) {
      t.fail("mach", std::string("no post-shock state: ") + e.what());
    }
  }
  t.finish();
}

}  // namespace dustlift::scene_detail
