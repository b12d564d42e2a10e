// Scene parsing: defaults, overrides, and errors that name file, line and key.
#include <gtest/gtest.h>

#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"

using namespace dustlift;

namespace {

const char* kMinimal = R"(
[run]
end_time = 0.2
allow_implausible = true   # Sod's tube in its own units (p = 1, R = 1)
[grid.x]
start = 0.0
end = 1.0
cells = 100
[grid.y]
start = 0.0
end = 0.01
cells = 1
[gas]
thermo = "calorically_perfect"
gas_constant = 1.0
[gas.transport]
model = "inviscid"
[initial]
kind = "riemann"
position = 0.5
left = { rho = 1.0, p = 1.0 }
right = { rho = 0.125, p = 0.1 }
)";

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    (void)parse_scene(text, "scene.toml", overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Scene, MinimalSceneResolvesDefaults) {
  const Scene s = parse_scene(kMinimal, "scene.toml");
  EXPECT_DOUBLE_EQ(s.run.end_time, 0.2);
  EXPECT_EQ(s.grid.x.cells, 100u);
  EXPECT_EQ(s.gas.thermo.model, ThermoModel::CaloricallyPerfect);
  EXPECT_DOUBLE_EQ(s.gas.thermo.gamma, 1.4);
  EXPECT_EQ(s.gas.scheme.reconstruction, Reconstruction::Muscl3);
  EXPECT_EQ(s.initial.kind, InitialCondition::Kind::Riemann);
  EXPECT_DOUBLE_EQ(s.initial.right.rho, 0.125);
  EXPECT_FALSE(s.particles.enabled);
  // The resolved scene lists defaults that the file did not give.
  EXPECT_NE(s.resolved_toml.find("cfl = 0.5"), std::string::npos);
  EXPECT_NE(s.resolved_toml.find("limiter = 'minmod'"), std::string::npos);
}

TEST(Scene, ResolvedSceneParsesBackToTheSameScene) {
  const Scene a = parse_scene(kMinimal, "scene.toml", {"gas.scheme.cfl=0.3"});
  const Scene b = parse_scene(a.resolved_toml, "resolved.toml");
  EXPECT_DOUBLE_EQ(b.gas.scheme.cfl, 0.3);
  EXPECT_EQ(b.grid.x.cells, a.grid.x.cells);
  EXPECT_DOUBLE_EQ(b.initial.left.p, a.initial.left.p);
}

TEST(Scene, SetOverridesAnyKey) {
  const Scene s = parse_scene(kMinimal, "scene.toml",
                              {"grid.x.cells=400", "gas.scheme.reconstruction=first_order",
                               "initial.left.p=2.5", "run.name=\"tube\""});
  EXPECT_EQ(s.grid.x.cells, 400u);
  EXPECT_EQ(s.gas.scheme.reconstruction, Reconstruction::FirstOrder);
  EXPECT_DOUBLE_EQ(s.initial.left.p, 2.5);
  EXPECT_EQ(s.run.name, "tube");
}

TEST(Scene, UnknownKeyNamesKeyAndLine) {
  std::string text = kMinimal;
  text += "[output]\nintervall = 0.1\n";
  const std::string e = error_of(text);
  EXPECT_NE(e.find("output.intervall"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
  EXPECT_NE(e.find("scene.toml:24"), std::string::npos) << e;
}

TEST(Scene, WrongTypeNamesKey) {
  const std::string e = error_of(kMinimal, {"run.end_time=\"soon\""});
  EXPECT_NE(e.find("run.end_time"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a number"), std::string::npos) << e;
}

TEST(Scene, NegativeSizeNamesKey) {
  const std::string e = error_of(kMinimal, {"grid.x.cells=-5"});
  EXPECT_NE(e.find("grid.x.cells"), std::string::npos) << e;
  const std::string e2 = error_of(kMinimal, {"initial.right.rho=-0.1"});
  EXPECT_NE(e2.find("initial.right.rho"), std::string::npos) << e2;
}

TEST(Scene, MissingRequiredTableOrKey) {
  EXPECT_NE(error_of("[run]\nend_time = 1.0\n").find("'grid'"), std::string::npos);
  const std::string e = error_of(kMinimal, {"initial.kind=shock"});
  EXPECT_NE(e.find("initial.state"), std::string::npos) << e;
}

TEST(Scene, UnknownChoiceListsAlternatives) {
  const std::string e = error_of(kMinimal, {"gas.scheme.limiter=superbee"});
  EXPECT_NE(e.find("gas.scheme.limiter"), std::string::npos) << e;
  EXPECT_NE(e.find("van_albada"), std::string::npos) << e;
}

TEST(Scene, StateNeedsExactlyOneOfRhoOrT) {
  const std::string e = error_of(kMinimal, {"initial.left.T=300"});
  EXPECT_NE(e.find("initial.left"), std::string::npos) << e;
}

TEST(Scene, TemperatureGivesDensityThroughGasConstant) {
  const Scene s = parse_scene(kMinimal, "scene.toml",
                              {"gas.gas_constant=288.19",
                               "initial={ kind = 'shock', mach = 1.44, position = 0.5, state = { p "
                               "= 101000.0, T = 300.0 } }"});
  EXPECT_NEAR(s.initial.state.rho, 1.16821, 1e-5);
}

TEST(Scene, PeriodicBoundariesComeInPairs) {
  const std::string e = error_of(kMinimal, {"boundary.left=periodic"});
  EXPECT_NE(e.find("boundary.right"), std::string::npos) << e;
}

TEST(Scene, SyntaxErrorNamesLine) {
  const std::string e = error_of("[run]\nend_time = = 1\n");
  EXPECT_NE(e.find("scene.toml:2"), std::string::npos) << e;
}

TEST(Scene, StretchedAxisMatchesPaperGrid) {
  // Paper section 3.1: 1901 x 161 points; 250 um cells on x in [0, 400] mm and y < 32 mm.
  const Scene s = parse_scene(kMinimal, "scene.toml",
                              {"grid.x={ start = -0.4, end = 0.4, cell_size = 250e-6, "
                               "uniform_start = 0.0, cells_below = 300 }",
                               "grid.y={ start = -0.002, end = 0.050, cell_size = 250e-6, "
                               "uniform_end = 0.032, cells_above = 24 }",
                               "initial.position=0.0"});
  const auto x = build_axis_nodes(s.grid.x);
  const auto y = build_axis_nodes(s.grid.y);
  EXPECT_EQ(x.size(), 1901u);
  EXPECT_EQ(y.size(), 161u);
  EXPECT_NEAR(x[301] - x[300], 250e-6, 1e-12);
  EXPECT_NEAR(x[300] - x[299], 250e-6, 1e-9);  // first stretched cell as wide as the uniform ones
  EXPECT_DOUBLE_EQ(x.front(), -0.4);
  EXPECT_DOUBLE_EQ(y.back(), 0.050);
}

TEST(Scene, OneNarrowCellAtAWallPutsCellCentresOnTheNodeCentredPoints) {
  // The paper's 161 y points read as the unknowns of a node-centred grid: a half cell at the
  // floor (-2 mm), then 250 um cells centred on the points, one of them on the layer top y = 0.
  const Scene s = parse_scene(
      kMinimal, "scene.toml",
      {"grid.y={ start = -0.002, end = 0.050, cell_size = 250e-6, uniform_start = -0.001875, "
       "cells_below = 1, uniform_end = 0.031875, cells_above = 24 }",
       "initial.position=0.5"});
  const auto y = build_axis_nodes(s.grid.y);
  ASSERT_EQ(y.size(), 161u);
  EXPECT_DOUBLE_EQ(y[0], -0.002);
  EXPECT_NEAR(y[1] - y[0], 125e-6, 1e-15);
  EXPECT_NEAR(y[2] - y[1], 250e-6, 1e-15);
  const Axis axis(y, 2);
  EXPECT_NEAR(axis.center(8), 0.0, 1e-15) << "a cell centre on the layer top";
  EXPECT_NEAR(axis.width(8), 250e-6, 1e-15);
  // Two or more stretched cells still may not be narrower than the uniform ones.
  AxisSpec two = s.grid.y;
  two.cells_below = 2;
  EXPECT_THROW(build_axis_nodes(two), std::invalid_argument);
}

TEST(Scene, RestToleranceIsCheckedAndNamed) {
  // Skipping within 1e-10 by default; run.exact = true skips only what rests exactly.
  EXPECT_EQ(parse_scene(kMinimal, "scene.toml").run.rest_tolerance, 1e-10);
  EXPECT_FALSE(parse_scene(kMinimal, "scene.toml").run.exact);
  EXPECT_EQ(parse_scene(kMinimal, "scene.toml", {"run.exact=true"}).run.rest_tolerance, 0.0);
  EXPECT_EQ(parse_scene(kMinimal, "scene.toml", {"run.rest_tolerance=0"}).run.rest_tolerance, 0.0);
  // Both at once contradict each other: refused, naming run.exact.
  const std::string both = error_of(kMinimal, {"run.exact=true", "run.rest_tolerance=1e-10"});
  EXPECT_NE(both.find("run.exact"), std::string::npos) << both;
  EXPECT_EQ(
      parse_scene(kMinimal, "scene.toml", {"run.exact=true", "run.rest_tolerance=0"}).run.exact,
      true);
  // The resolved scene of an exact run runs again as it is (its tolerance derived, not 1e-10).
  const Scene exact = parse_scene(kMinimal, "scene.toml", {"run.exact=true"});
  EXPECT_EQ(parse_scene(exact.resolved_toml, "resolved.toml").run.rest_tolerance, 0.0);
  EXPECT_DOUBLE_EQ(
      parse_scene(kMinimal, "scene.toml", {"run.rest_tolerance=1e-10"}).run.rest_tolerance, 1e-10);
  for (const char* bad : {"run.rest_tolerance=1e-3", "run.rest_tolerance=-1e-12"}) {
    const std::string e = error_of(kMinimal, {bad});
    EXPECT_NE(e.find("run.rest_tolerance"), std::string::npos) << e;
  }
  // A tolerance widens what skipping counts as resting: without skipping it means nothing.
  const std::string e = error_of(kMinimal, {"run.rest_tolerance=1e-10", "run.skip_at_rest=false"});
  EXPECT_NE(e.find("run.rest_tolerance"), std::string::npos) << e;
  EXPECT_NE(e.find("skip_at_rest"), std::string::npos) << e;
  EXPECT_EQ(parse_scene(kMinimal, "scene.toml", {"run.skip_at_rest=false"}).run.rest_tolerance,
            0.0);
}

namespace {

/// Air at rest in a 10 x 4 mm box with a dust layer; `layer` and `grid_y` are the layer's
/// and the y axis's keys, `state` the gas state.
std::string dusty_box(const std::string& layer, const std::string& grid_y,
                      const std::string& state = "{ p = 101325.0, T = 300.0 }",
                      const std::string& run = "") {
  return "[run]\nend_time = 1e-6\n" + run +
         "\n[grid.x]\nstart = 0.0\nend = 0.01\ncells = 20\n[grid.y]\n" + grid_y +
         "\nend = 0.004\ncells = 16\n[initial]\nstate = " + state +
         "\n[particles]\ndiameter = 100e-6\ndensity = 1000.0\n[particles.contact]\nk_n = "
         "5e4\ndamping = 1e-4\n"
         "[particles.layer]\nx_min = 0.002\nx_max = 0.008\n" +
         layer + "\n";
}

}  // namespace

TEST(Scene, LayerThicknessSetsTheBottomAndTheFloor) {
  // thickness alone: y_min = y_max - thickness and grid.y.start follows (both derived).
  const Scene s = parse_scene(dusty_box("y_max = 0.0\nthickness = 1e-3", ""), "scene.toml");
  EXPECT_DOUBLE_EQ(s.particles.layer.y_min, -1e-3);
  EXPECT_DOUBLE_EQ(s.grid.y.start, -1e-3);
  EXPECT_NE(s.resolved_toml.find("grid.y.start = -0.001   # from particles.layer.thickness"),
            std::string::npos)
      << s.resolved_toml;
  EXPECT_NE(
      s.resolved_toml.find("particles.layer.y_min = -0.001   # from particles.layer.thickness"),
      std::string::npos);
  // The top defaults to y = 0; another top moves the bottom and the floor with it.
  const Scene moved =
      parse_scene(dusty_box("y_max = 0.5e-3\nthickness = 1.5e-3", ""), "scene.toml");
  EXPECT_DOUBLE_EQ(moved.particles.layer.y_min, 0.5e-3 - 1.5e-3);
  EXPECT_DOUBLE_EQ(moved.grid.y.start, 0.5e-3 - 1.5e-3);
  // One key to vary: the floor follows a --set of the thickness.
  const Scene thicker = parse_scene(dusty_box("thickness = 1e-3", ""), "scene.toml",
                                    {"particles.layer.thickness=2e-3"});
  EXPECT_DOUBLE_EQ(thicker.particles.layer.y_min, -2e-3);
  EXPECT_DOUBLE_EQ(thicker.grid.y.start, -2e-3);
  // The resolved scene derives both again.
  const Scene again =
      parse_scene(thicker.resolved_toml, "resolved.toml", {"particles.layer.thickness=0.5e-3"});
  EXPECT_DOUBLE_EQ(again.grid.y.start, -0.5e-3);
  // Keys that agree with the thickness are accepted.
  const Scene agreeing =
      parse_scene(dusty_box("y_min = -1e-3\nthickness = 1e-3", "start = -1e-3"), "scene.toml");
  EXPECT_DOUBLE_EQ(agreeing.grid.y.start, -1e-3);
  // Without thickness, y_min and grid.y.start are as before.
  const Scene classic =
      parse_scene(dusty_box("y_min = -1e-3\ny_max = 0.0", "start = -2e-3"), "scene.toml");
  EXPECT_DOUBLE_EQ(classic.particles.layer.y_min, -1e-3);
  EXPECT_DOUBLE_EQ(classic.grid.y.start, -2e-3);
}

TEST(Scene, LayerThicknessRefusesContradictoryKeysNamingBoth) {
  const std::string bottom = error_of(dusty_box("y_min = -2e-3\nthickness = 1e-3", ""));
  EXPECT_NE(bottom.find("scene.toml:"), std::string::npos) << bottom;
  EXPECT_NE(
      bottom.find(
          "key 'particles.layer.y_min': -0.002 m contradicts particles.layer.thickness = 0.001 m"),
      std::string::npos)
      << bottom;
  const std::string floor = error_of(dusty_box("thickness = 1e-3", "start = -2e-3"));
  EXPECT_NE(
      floor.find("key 'grid.y.start': -0.002 m contradicts particles.layer.thickness = 0.001 m"),
      std::string::npos)
      << floor;
  EXPECT_NE(floor.find("leave grid.y.start out"), std::string::npos) << floor;
  const std::string via_set = error_of(dusty_box("thickness = 1e-3", ""), {"grid.y.start=-3e-3"});
  EXPECT_NE(via_set.find("--set 'grid.y.start=-3e-3': key 'grid.y.start'"), std::string::npos)
      << via_set;
  EXPECT_NE(error_of(dusty_box("thickness = -1e-3", "")).find("key 'particles.layer.thickness'"),
            std::string::npos);
  // Neither a floor nor a thickness: the message names both ways.
  const std::string none = error_of(dusty_box("y_min = -1e-3", ""));
  EXPECT_NE(none.find("key 'grid.y.start': missing: give grid.y.start (the floor, m), or "
                      "particles.layer.thickness"),
            std::string::npos)
      << none;
}

TEST(Scene, ImplausiblePressureAndTemperatureAreRefusedNamingTheUnit) {
  const std::string floor = "start = -1e-3";
  const std::string atm = error_of(dusty_box("y_min = -1e-3", floor, "{ p = 1.0, T = 300.0 }"));
  EXPECT_NE(atm.find("scene.toml:13: key 'initial.state.p': 1 Pa is below 1 kPa"),
            std::string::npos)
      << atm;
  EXPECT_NE(atm.find("pressures are in Pa (did you mean 1 atm = 101325 Pa, 1 bar = 100000 Pa or 1 "
                     "kPa = 1000 Pa?)"),
            std::string::npos)
      << atm;
  EXPECT_NE(atm.find("if 1 Pa is meant, set run.allow_implausible = true"), std::string::npos)
      << atm;
  const std::string celsius =
      error_of(dusty_box("y_min = -1e-3", floor, "{ p = 101325.0, T = 20.0 }"));
  EXPECT_NE(celsius.find("key 'initial.state.T': 20 K is below 100 K"), std::string::npos)
      << celsius;
  EXPECT_NE(celsius.find("did you mean 20 degC = 293.15 K?"), std::string::npos) << celsius;
  const std::string dust =
      error_of(dusty_box("y_min = -1e-3", floor), {"particles.temperature=25"});
  EXPECT_NE(
      dust.find(
          "--set 'particles.temperature=25': key 'particles.temperature': 25 K is below 100 K"),
      std::string::npos)
      << dust;
  // Confirmed: accepted (and a plausible value needs no confirmation).
  const Scene confirmed = parse_scene(dusty_box("y_min = -1e-3", floor, "{ p = 500.0, T = 300.0 }"),
                                      "scene.toml", {"run.allow_implausible=true"});
  EXPECT_DOUBLE_EQ(confirmed.initial.state.p, 500.0);
  EXPECT_NO_THROW(parse_scene(dusty_box("y_min = -1e-3", floor), "scene.toml"));
}
