// Checkpoint/restart: a run continued from a checkpoint ends bitwise identical to the run that
// was never interrupted (gas conserved fields, parcel state); a process killed while writing
// leaves the previous checkpoint usable; damaged or foreign files are rejected with exit 2.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "insitu/checkpoint.hpp"
#include "solver/core/errors.hpp"
#include "solver/sim/checkpoint_keeper.hpp"
#include "solver/sim/simulation.hpp"
#include "support/run_cli.hpp"
#include "support/snapshot_compare.hpp"

namespace fs = std::filesystem;
using namespace dustlift;
using dustlift::testing::differing;
using dustlift::testing::expect_bitwise_equal;
using dustlift::testing::fresh_dir;
using dustlift::testing::read_bytes;
using dustlift::testing::run_cli;
using dustlift::testing::write_file;

namespace {

/// The closed box of tests/verification/test_coupling.cpp (periodic x, slip walls, a loose
/// layer, every effect on), with heat transfer and a gas flow over the layer.
const char* kBox = R"(
[run]
end_time = 1.0
[grid]
x = { start = 0.0, end = 0.008, cells = 16 }
y = { start = 0.0, end = 0.004, cells = 8 }
[gas]
thermo = "thermally_perfect"
[boundary]
left = "periodic"
right = "periodic"
bottom = "slip_wall"
top = "slip_wall"
[initial]
kind = "uniform"
state = { p = 101325.0, T = 330.0, u = 15.0, v = -3.0 }
[particles]
diameter = 100e-6
density = 980.0
temperature = 300.0
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[particles.layer]
x_min = 0.0
x_max = 0.008
y_min = 0.0
y_max = 0.002
volume_fraction = 0.35
[coupling]
magnus = true
pressure_force = true
rotation_torque = true
heat_transfer = true
)";

/// Gas only: a Mach 1.44 shock in a viscous thermally perfect gas (Sod-like, 2-D grid).
const char* kShock = R"(
[run]
end_time = 2e-5
[grid]
x = { start = 0.0, end = 0.02, cells = 80 }
y = { start = 0.0, end = 0.005, cells = 10 }
[gas]
thermo = "thermally_perfect"
[gas.transport]
model = "gordon_wilke"
[boundary]
left = "inflow"
right = "outflow"
bottom = "no_slip_wall"
top = "slip_wall"
[initial]
kind = "shock"
mach = 1.44
position = 0.005
axis = "x"
state = { p = 101325.0, T = 300.0 }
[output]
vtk = false
)";

void agitate(ParcelSystem& ps) {
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const double a = std::sin(12.9898 * static_cast<double>(k) + 1.0),
                 b = std::cos(78.233 * static_cast<double>(k));
    ps.vx[k] = 2.0 * a;
    ps.vy[k] = 2.0 * b;
    ps.omega[k] = 2000.0 * a * b;
  }
}

/// Runs `total` steps uninterrupted and, separately, `first` steps, a checkpoint through an
/// HDF5 file, a fresh Simulation from the stored scene text and `total - first` more steps.
void check_restart_is_bitwise(const std::string& text, int first, int total, bool with_parcels) {
  const auto dir = fresh_dir("restart_bitwise");
  const Scene scene = parse_scene(text, "scene.toml");
  Simulation uninterrupted(scene);
  if (with_parcels) agitate(*uninterrupted.parcels());
  Simulation interrupted(scene);
  if (with_parcels) agitate(*interrupted.parcels());
  const double dt_max = 1.0;
  for (int k = 0; k < first; ++k) {
    uninterrupted.advance(dt_max);
    interrupted.advance(dt_max);
  }
  const std::string path = (dir / "checkpoint.h5").string();
  write_checkpoint(path, interrupted.snapshot());
  const Snapshot stored = read_checkpoint(path);
  const Scene again = parse_scene(stored.text.at("scene/text"), stored.text.at("scene/name"));
  Simulation restarted(again);
  restarted.restore(stored);
  EXPECT_EQ(restarted.step(), first);
  for (int k = first; k < total; ++k) {
    uninterrupted.advance(dt_max);
    restarted.advance(dt_max);
  }
  EXPECT_EQ(restarted.time(), uninterrupted.time());
  EXPECT_EQ(restarted.step(), uninterrupted.step());
  const Snapshot a = uninterrupted.snapshot(), b = restarted.snapshot();
  expect_bitwise_equal(a, b);
  // The comparison is not vacuous: the state moved after the checkpoint.
  std::size_t moved = differing(a.f64.at("gas/conserved_1"), stored.f64.at("gas/conserved_1"));
  if (with_parcels) moved += differing(a.f64.at("parcels/x"), stored.f64.at("parcels/x"));
  std::printf(
      "restart after %d of %d steps: %zu gas+parcel values changed after the checkpoint, 0 differ "
      "between restarted and uninterrupted (%zu arrays compared)\n",
      first, total, moved, a.f64.size() + a.i64.size() + a.i32.size() + a.i8.size());
  EXPECT_GT(moved, 100u);
  fs::remove_all(dir);
}

}  // namespace

TEST(CheckpointRestart, CoupledBoxContinuesBitwise) {
  check_restart_is_bitwise(kBox, 120, 300, true);
}

TEST(CheckpointRestart, PolydisperseBoxContinuesBitwise) {
  // Three log-normal classes: their real diameters, classes and counts come back from the
  // checkpoint, and the contacts between classes continue bit for bit.
  // The box's one diameter gives way to the distribution (its mass median).
  std::string box = kBox;
  const std::size_t at = box.find("\ndiameter = 100e-6");
  ASSERT_NE(at, std::string::npos);
  box.erase(at + 1, box.find('\n', at + 1) - at);
  check_restart_is_bitwise(box + "[particles.size_distribution]\nmedian = 60e-6\ngeometric_std = 1.5\nclasses = 3\n",
                           120, 300, true);
}

TEST(CheckpointRestart, ClassParcelsRestitutionAndCohesionContinueBitwise) {
  // Three classes in parcels of their own sizes (columns of one class), the restitution per
  // pair and van der Waals cohesion with a tail across gaps: the parcel sizes, counts and the
  // pairs' dashpots come back from the checkpoint, and the run continues bit for bit.
  std::string box = kBox;
  for (const char* line : {"\ndiameter = 100e-6", "\ndamping = 1.0e-4"}) {
    const std::size_t at = box.find(line);
    ASSERT_NE(at, std::string::npos) << line;
    box.erase(at + 1, box.find('\n', at + 1) - at);
  }
  box.replace(box.find("volume_fraction = 0.35"), 22,
              "volume_fraction = 0.35\narrangement = \"columnar\"");
  box.replace(box.find("k_t = 100.0"), 11, "k_t = 100.0\nrestitution = 0.8");
  box.replace(box.find("temperature = 300.0"), 19, "temperature = 300.0\nparcel_ratio = [3, 2, 1.5]");
  check_restart_is_bitwise(box + "[particles.size_distribution]\nmedian = 60e-6\ngeometric_std = 1.5\n"
                                 "classes = 3\n[particles.cohesion]\nhamaker = 1e-20\ncutoff = 1e-6\n",
                           120, 300, true);
}

TEST(CheckpointRestart, GasOnlyShockContinuesBitwise) {
  check_restart_is_bitwise(kShock, 40, 100, false);
}

TEST(CheckpointRestart, CliRestartMatchesUninterruptedRun) {
  // Through the CLI and run(): output cadence, next output index and the final checkpoint.
  const auto dir = fresh_dir("cli_restart");
  write_file(dir / "box.toml", kBox);
  const std::string common =
      " --threads 2 --set run.end_time=4e-5 --set output.interval=1e-5 --set output.vtk=false";
  auto r =
      run_cli("run " + (dir / "box.toml").string() + " --out " + (dir / "full").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("run " + (dir / "box.toml").string() + " --out " + (dir / "part").string() + common +
              " --set run.max_steps=37");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("run --restart " + (dir / "part" / "checkpoint.h5").string() + " --out " +
              (dir / "rest").string() + " --threads 1 --set run.max_steps=0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Snapshot full = read_checkpoint((dir / "full" / "checkpoint.h5").string());
  const Snapshot part = read_checkpoint((dir / "part" / "checkpoint.h5").string());
  const Snapshot rest = read_checkpoint((dir / "rest" / "checkpoint.h5").string());
  EXPECT_EQ(part.i64.at("run/step")[0], 37);
  EXPECT_EQ(rest.f64.at("run/time")[0], full.f64.at("run/time")[0]);
  EXPECT_DOUBLE_EQ(rest.f64.at("run/time")[0], 4e-5);
  EXPECT_EQ(rest.i64.at("run/next_output")[0], full.i64.at("run/next_output")[0]);
  // The physics bit for bit; the series differ by the final frame the step-limited part
  // wrote at step 37 (tests/stress/test_interrupt_restart.cpp compares series).
  expect_bitwise_equal(full, rest, false);
  // The restart may only change when to stop and what to write.
  r = run_cli("run --restart " + (dir / "part" / "checkpoint.h5").string() + " --out " +
              (dir / "bad").string() + " --set gas.scheme.cfl=0.3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("gas.scheme.cfl"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
  fs::remove_all(dir);
}

TEST(CheckpointRestart, KilledWhileWritingLeavesPreviousCheckpointUsable) {
  // The CLI checkpoints after every step (tiny interval); SIGKILL at random moments, then
  // restart from whatever checkpoint.h5 is there. Every trial must restart and finish.
  const auto dir = fresh_dir("kill9");
  write_file(dir / "box.toml", kBox);
  std::mt19937 rng(20261125);
  std::uniform_int_distribution<int> delay_ms(150, 900);
  const int trials = 8;
  int killed_with_checkpoint = 0, killed_during_tmp = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const fs::path out = dir / ("run" + std::to_string(trial));
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      const std::string scene = (dir / "box.toml").string(), o = out.string();
      const int devnull = open("/dev/null", O_WRONLY);
      dup2(devnull, 1);
      dup2(devnull, 2);
      execl(DUSTLIFT_BINARY, DUSTLIFT_BINARY, "run", scene.c_str(), "--out", o.c_str(), "--threads",
            "1", "--set", "run.end_time=1e-3", "--set", "output.vtk=false", "--set",
            "output.checkpoint_interval=1e-9", static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "trial " << trial << ": the run ended before the kill";
    if (!fs::exists(out / "checkpoint.h5")) continue;  // killed before the first checkpoint
    ++killed_with_checkpoint;
    killed_during_tmp += fs::exists(out / "checkpoint.h5.tmp");
    const Snapshot s = read_checkpoint((out / "checkpoint.h5").string());
    char end_time[64];
    std::snprintf(end_time, sizeof end_time, "%.17g", s.f64.at("run/time")[0] + 2e-6);
    const auto r = run_cli("run --restart " + (out / "checkpoint.h5").string() + " --out " +
                           (dir / "cont").string() + " --threads 1 --set run.end_time=" + end_time +
                           " --set output.checkpoint_interval=0");
    ASSERT_EQ(r.exit_code, 0) << "trial " << trial << "\n" << r.output;
    const Snapshot end = read_checkpoint((dir / "cont" / "checkpoint.h5").string());
    EXPECT_DOUBLE_EQ(end.f64.at("run/time")[0], s.f64.at("run/time")[0] + 2e-6);
    EXPECT_GT(end.i64.at("run/step")[0], s.i64.at("run/step")[0]);
    fs::remove_all(dir / "cont");
  }
  std::printf(
      "kill -9: %d trials, %d left a checkpoint (all restarted), %d were killed with a .tmp "
      "present\n",
      trials, killed_with_checkpoint, killed_during_tmp);
  EXPECT_GE(killed_with_checkpoint, trials / 2);
  fs::remove_all(dir);
}

TEST(CheckpointRestart, DamagedOrForeignFilesExitWithCode2) {
  const auto dir = fresh_dir("bad_checkpoint");
  write_file(dir / "box.toml", kBox);
  auto r = run_cli("run " + (dir / "box.toml").string() + " --out " + (dir / "good").string() +
                   " --threads 1 --set run.max_steps=3 --set output.vtk=false");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string good = read_bytes(dir / "good" / "checkpoint.h5");
  ASSERT_GT(good.size(), kCheckpointHeaderBytes + 1000);

  struct Case {
    std::string name, bytes, message;
  };
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  // An HDF5 file of another program: the series file a run writes.
  fs::create_directories(dir / "other");
  const std::string foreign_h5 = [&] {
    r = run_cli("run " + (dir / "box.toml").string() + " --out " + (dir / "other" / "o").string() +
                " --threads 1 --set run.max_steps=2 --set output.vtk=false");
    return read_bytes(dir / "other" / "o" / "series" / "series.h5");
  }();
  ASSERT_FALSE(foreign_h5.empty());
  // A valid header in front of an HDF5 file without our layout (sealed by the same code).
  const std::vector<Case> cases = {
      {"truncated", good.substr(0, good.size() * 2 / 3), "truncated"},
      {"text", "[run]\nend_time = 1.0\n", "not a dustlift checkpoint"},
      {"empty", "", "not a dustlift checkpoint"},
      {"flipped_bit", flipped, "checksum"},
      {"foreign_hdf5", foreign_h5, "HDF5 file but not a dustlift checkpoint"},
  };
  for (const auto& c : cases) {
    const fs::path file = dir / (c.name + ".h5");
    write_file(file, c.bytes);
    const fs::path out = dir / ("out_" + c.name);
    r = run_cli("run --restart " + file.string() + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.name << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.name << ": one line\n"
                                                                     << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  // Sealed foreign HDF5: passes the checksum, fails on the layout.
  const fs::path sealed = dir / "sealed.h5";
  write_file(sealed, std::string(kCheckpointHeaderBytes, '\0') + foreign_h5);
  seal_checkpoint(sealed.string());
  r = run_cli("run --restart " + sealed.string() + " --out " + (dir / "out_sealed").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("without the dustlift checkpoint layout"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(CheckpointRestart, NumericalFailureLeavesLastGoodCheckpoint) {
  // run() checkpoints every step; after the 5th checkpoint the test poisons one gas cell
  // (negative density), so the next step throws NumericalFailure. No checkpoint may follow
  // the failure, and the file on disk must be the 5th, still readable and restartable.
  const auto dir = fresh_dir("failure_checkpoint");
  const std::string path = (dir / "checkpoint.h5").string();
  Scene scene = parse_scene(kShock, "shock.toml", {"output.checkpoint_interval=1e-12"});
  Simulation sim(scene);
  int written = 0;
  long long poisoned_at = -1;
  sim.add_observer(std::make_unique<CheckpointKeeper>(scene.output, [&](const Snapshot& s) {
    write_checkpoint(path, s);
    if (++written == 5) {
      poisoned_at = sim.step();
      sim.gas().conserved(0)(40, 5) = -1.0;
    }
  }));
  EXPECT_THROW(sim.run(dir.string()), NumericalFailure);
  EXPECT_EQ(written, 5);
  const Snapshot last = read_checkpoint(path);
  EXPECT_EQ(last.i64.at("run/step")[0], poisoned_at);
  Simulation restarted(scene);
  restarted.restore(last);
  EXPECT_EQ(restarted.step(), poisoned_at);
  EXPECT_GT(restarted.gas().conserved(0)(40, 5), 0.0) << "the poison came after the checkpoint";
  restarted.advance(1.0);  // and it continues
  EXPECT_EQ(restarted.step(), poisoned_at + 1);
  fs::remove_all(dir);
}
