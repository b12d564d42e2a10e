// Simulation::run's schedule: output and end times are reached exactly (the same doubles in
// every run, interrupted or not), checkpoints follow the simulated and the wall-clock cadence
// without shortening a step, and a stop request ends the run after its step with a checkpoint.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/sim/checkpoint_keeper.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/time_targets.hpp"

using namespace dustlift;

namespace {

/// Gas only: a Mach 1.44 shock on 40 x 4 cells (about 2e-7 s steps), 1e-5 s.
const char* kShock = R"(
[run]
end_time = 1e-5
[grid]
x = { start = 0.0, end = 0.02, cells = 40 }
y = { start = 0.0, end = 0.002, cells = 4 }
[gas]
thermo = "calorically_perfect"
[gas.transport]
model = "inviscid"
[initial]
kind = "shock"
mach = 1.44
position = 0.005
state = { p = 101325.0, T = 300.0 }
[output]
interval = 2e-6
vtk = false
)";

/// Records the times it is called at.
struct Times final : Observer {
  std::vector<double>* outputs;
  std::vector<double>* finishes;
  Times(std::vector<double>* o, std::vector<double>* f) : outputs(o), finishes(f) {}
  void on_start(const StateView& v) override { outputs->push_back(v.time); }
  void on_output(const StateView& v) override { outputs->push_back(v.time); }
  void on_finish(const StateView& v) override { finishes->push_back(v.time); }
};

int checkpoints_written(const std::vector<std::string>& overrides, RunEnd* how = nullptr,
                        std::function<bool(const Simulation&)> stop = {}) {
  Simulation sim(parse_scene(kShock, "shock.toml", overrides));
  int written = 0;
  sim.add_observer(
      std::make_unique<CheckpointKeeper>(sim.scene().output, [&](const Snapshot&) { ++written; }));
  if (stop) sim.set_stop_request([&] { return stop(sim); });
  const RunEnd end = sim.run("");
  if (how != nullptr) *how = end;
  return written;
}

}  // namespace

TEST(TimeTargets, TheNextMultipleIsFoundAgainstTheProductsNotTheQuotient) {
  const double interval = 5e-5;
  EXPECT_EQ(first_multiple_after(0.0, interval), 1);
  EXPECT_EQ(first_multiple_after(multiple_time(3, interval), interval),
            4);  // 1.5000000000000002e-4 / 5e-5 < 3
  EXPECT_EQ(first_multiple_after(std::nextafter(multiple_time(3, interval), 0.0), interval), 3);
  EXPECT_EQ(first_multiple_after(1.5e-4, interval), 3) << "1.5e-4 lies a rounding below 3 * 5e-5";
  EXPECT_EQ(first_multiple_after(7.3e-4, interval), 15);
}

TEST(TimeTargets, AnEndTimeOnTheOutputGridIsThatOutputTime) {
  EXPECT_NE(1.5e-4, 3 * 5e-5);
  EXPECT_EQ(end_target(1.5e-4, 5e-5), 3 * 5e-5);
  EXPECT_EQ(end_target(1.2e-4, 5e-5), 1.2e-4);  // between two outputs: kept
  EXPECT_EQ(end_target(1.5e-4, 0.0), 1.5e-4);   // no outputs
}

TEST(RunSchedule, OutputsAndTheEndAreReachedExactlyAndTheEndOutputIsNotRepeated) {
  std::vector<double> outputs, finishes;
  Simulation sim(parse_scene(kShock, "shock.toml"));
  sim.add_observer(std::make_unique<Times>(&outputs, &finishes));
  EXPECT_EQ(sim.run(""), RunEnd::Completed);
  ASSERT_EQ(outputs.size(), 6u);  // t = 0 and 5 outputs, the last one at the end
  for (std::size_t k = 0; k < outputs.size(); ++k)
    EXPECT_EQ(outputs[k], multiple_time(static_cast<long long>(k), 2e-6)) << k;
  EXPECT_EQ(sim.time(), end_target(1e-5, 2e-6));
  ASSERT_EQ(finishes.size(), 1u);
  EXPECT_EQ(finishes[0], sim.time());
  EXPECT_EQ(sim.next_output(), 6)
      << "the output at the end is counted, so an extension goes on to the next";
  EXPECT_GT(sim.step(), 40);
}

TEST(RunSchedule, CheckpointsFollowTheSimulatedAndWallCadencesAndTheEnd) {
  Simulation probe(parse_scene(kShock, "shock.toml"));
  EXPECT_EQ(probe.scene().output.checkpoint_interval, 2e-6) << "default: at every output";
  EXPECT_EQ(probe.scene().output.checkpoint_wall_interval, 300.0);
  // By simulated time: the first steps at or after 2, 4, 6, 8 us, and once at the end (10 us).
  EXPECT_EQ(checkpoints_written({}), 5);
  EXPECT_EQ(checkpoints_written({"output.checkpoint_interval=3e-6"}), 4);  // 3, 6, 9 us + end
  EXPECT_EQ(
      checkpoints_written({"output.checkpoint_interval=0", "output.checkpoint_wall_interval=0"}),
      1);
  // By wall time: a tiny cadence checkpoints after every step (the last one only once).
  Simulation sim(
      parse_scene(kShock, "shock.toml",
                  {"output.checkpoint_interval=0", "output.checkpoint_wall_interval=1e-9"}));
  int written = 0;
  sim.add_observer(
      std::make_unique<CheckpointKeeper>(sim.scene().output, [&](const Snapshot&) { ++written; }));
  sim.run("");
  EXPECT_EQ(written, sim.step());
}

TEST(RunSchedule, CheckpointsDoNotChangeTheSteps) {
  Simulation a(parse_scene(kShock, "shock.toml", {"output.checkpoint_wall_interval=1e-9"}));
  Simulation b(parse_scene(kShock, "shock.toml",
                           {"output.checkpoint_interval=0", "output.checkpoint_wall_interval=0"}));
  a.add_observer(std::make_unique<CheckpointKeeper>(a.scene().output, [](const Snapshot&) {}));
  b.add_observer(std::make_unique<CheckpointKeeper>(b.scene().output, [](const Snapshot&) {}));
  a.run("");
  b.run("");
  EXPECT_EQ(a.step(), b.step());
  EXPECT_EQ(a.gas().conserved(0).raw(), b.gas().conserved(0).raw());
}

TEST(RunSchedule, AStopRequestEndsTheRunAfterItsStepWithACheckpointAndNoFinalFrame) {
  std::vector<double> outputs, finishes;
  Simulation sim(parse_scene(kShock, "shock.toml"));
  sim.add_observer(std::make_unique<Times>(&outputs, &finishes));
  long long checkpointed_at = -1;
  sim.add_observer(std::make_unique<CheckpointKeeper>(
      sim.scene().output, [&](const Snapshot& s) { checkpointed_at = s.i64.at("run/step")[0]; }));
  sim.set_stop_request([&] { return sim.step() >= 17; });
  EXPECT_EQ(sim.run(""), RunEnd::Interrupted);
  EXPECT_EQ(sim.step(), 17);
  EXPECT_EQ(checkpointed_at, 17);
  EXPECT_TRUE(finishes.empty());
  EXPECT_LT(sim.time(), 1e-5);
  RunEnd how{};
  EXPECT_EQ(checkpoints_written({"run.max_steps=5", "output.checkpoint_interval=0",
                                 "output.checkpoint_wall_interval=0"},
                                &how),
            1);
  EXPECT_EQ(how, RunEnd::StepLimit);
}
