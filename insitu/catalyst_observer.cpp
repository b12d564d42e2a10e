// The Catalyst observer: loads the adaptor module (libdustlift_catalyst.so) when a scene has
// an [insitu.catalyst] section, gathers the gas and parcel arrays at the steps the pipelines
// want, and hands them over. Nothing of ParaView is loaded into a run without the section.
#include <dlfcn.h>
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "insitu/catalyst_adaptor.hpp"
#include "insitu/gas_cells.hpp"
#include "insitu/observers.hpp"
#include "insitu/provenance_of.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/time_targets.hpp"

namespace fs = std::filesystem;

namespace dustlift {
namespace {

bool has_display() {
  const char* d = std::getenv("DISPLAY");
  return d != nullptr && *d != '\0';
}

bool program_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::string_view rest(path);
  while (!rest.empty()) {
    const auto colon = rest.find(':');
    const fs::path dir(std::string(rest.substr(0, colon)));
    if (access((dir / name).c_str(), X_OK) == 0) return true;
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 1);
  }
  return false;
}

/// Where the module may be: $DUSTLIFT_CATALYST_MODULE, beside the executable, the installed
/// lib folder, and the build tree's copy (tests run from other folders).
std::vector<std::string> module_candidates() {
  std::vector<std::string> c;
  if (const char* env = std::getenv("DUSTLIFT_CATALYST_MODULE"); env != nullptr && *env != '\0')
    c.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    c.push_back((exe.parent_path() / "libdustlift_catalyst.so").string());
    c.push_back((exe.parent_path().parent_path() / "lib" / "dustlift" / "libdustlift_catalyst.so")
                    .string());
  }
#ifdef DUSTLIFT_CATALYST_MODULE_BUILD
  c.emplace_back(DUSTLIFT_CATALYST_MODULE_BUILD);
#endif
  return c;
}

class CatalystObserver final : public Observer {
 public:
  CatalystObserver(const Scene& scene, std::string output_dir, ParcelArraysOf parcels_of)
      : config_(scene.insitu.catalyst),
        output_dir_(std::move(output_dir)),
        parcels_of_(std::move(parcels_of)) {
    frames_ = config_.interval > 0.0 ? Cadence::simulated(config_.interval)
                                     : Cadence::steps(config_.interval_steps);
    const std::string where = scene.source_file + ": insitu.catalyst: ";
#ifndef DUSTLIFT_WITH_CATALYST
    throw SceneError(
        where +
        "this dustlift was built without ParaView Catalyst (paraview-dev and the packages "
        "scripts/install-deps.sh installs were not found at configure time)");
#else
    // A render without an X server aborts the process: refuse before anything is written.
    if (!has_display() && !program_on_path("Xvfb")) {
      throw SceneError(
          where +
          "no X display (DISPLAY is unset) and no Xvfb to start one for in-situ renders: "
          "install xvfb (scripts/install-deps.sh) or run under a display");
    }
    std::string tried;
    for (const auto& path : module_candidates()) {
      // RTLD_GLOBAL: the Python extension modules ParaView imports need libpython's symbols,
      // which only the module brings in.
      handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
      if (handle_ != nullptr) {
        module_path_ = path;
        break;
      }
      tried += "\n  " + path + ": " + dlerror();
    }
    if (handle_ == nullptr)
      throw SceneError(where + "cannot load the Catalyst adaptor module:" + tried);
    factory_ = reinterpret_cast<CatalystFactory>(dlsym(handle_, kCatalystFactorySymbol));
    if (factory_ == nullptr)
      throw SceneError(where + module_path_ + " has no " + kCatalystFactorySymbol);
#endif
  }
  // The module stays loaded: ParaView and the embedded Python do not support being unloaded.
  ~CatalystObserver() override {
    pipelines_.reset();
  }

  void on_start(const StateView& view) override {
    open(view);
    frames_.set_next_index(1);
    deliver(view, false);
  }
  void on_resume(const StateView& view, const std::string&) override {
    // The restored step was delivered (if due) by the run that wrote the checkpoint.
    open(view);
    frames_.start({view.time, view.step, 0.0});
  }
  void on_output(const StateView&) override {}
  bool reads_step(const StateView& view) const override {
    if (at_end(view)) return false;
    return frames_.due({view.time, view.step, 0.0});
  }
  void on_step(const StateView& view) override {
    if (!reads_step(view))
      return;  // not due, or the end, which on_finish delivers to every pipeline
    frames_.done({view.time, view.step, 0.0});
    deliver(view, false);
  }
  void on_finish(const StateView& view) override {
    if (!pipelines_) return;
    deliver(view, true);
    pipelines_->finalize();
    log(view,
        fmt::format("catalyst: {} frames gathered in {:.3f} s ({:.2f} ms each)", gathered_,
                    gather_seconds_,
                    gathered_ > 0 ? 1e3 * gather_seconds_ / static_cast<double>(gathered_) : 0.0));
  }

 private:
  /// The run's last step (its end time or step limit), which on_finish delivers.
  static bool at_end(const StateView& view) {
    const RunConfig& run = view.scene->run;
    return view.time >= end_target(run.end_time, view.scene->output.interval) ||
           (run.max_steps > 0 && view.step >= run.max_steps);
  }

  void log(const StateView& view, const std::string& line) const {
    if (view.log != nullptr) (*view.log)(line);
  }

  void open(const StateView& view) {
    if (pipelines_ || factory_ == nullptr) return;
    CatalystSettings s;
    s.scripts = config_.scripts;
    s.live = config_.live;
    s.live_url = config_.live_url;
    s.output_dir = fs::absolute(view.output_dir.empty() ? output_dir_ : view.output_dir).string();
    if (view.log != nullptr) {
      s.log = *view.log;
    } else {
      s.log = [](const std::string& line) { fmt::print(stderr, "{}\n", line); };
    }
    std::string error;
    pipelines_.reset(factory_(s, error));
    if (!pipelines_)
      log(view, "catalyst: the adaptor did not start (" + error + "); the run goes on without it");
  }

  void deliver(const StateView& view, bool last) {
    if (!pipelines_ || !pipelines_->wants(view.time, view.step, last)) return;
    const auto t0 = std::chrono::steady_clock::now();
    if (!view.derived) throw std::invalid_argument("catalyst: the state view has no fields");
    gather_gas_cells(
        *view.derived, [&](int i, int j) { return view.gas->sound_speed(i, j); }, gas_);
    CatalystFrame f;
    f.time = view.time;
    f.step = view.step;
    f.last = last;
    f.gas = &gas_;
    ParcelArraysView parcels;
    if (view.parcels != nullptr && parcels_of_) {
      parcels = parcels_of_(view);
      parcels.check_sizes();
      f.parcels = &parcels;
    }
    const VtkFileInfo info = vtk_file_info_of(view);
    f.code_version = info.code_version;
    f.command_line = info.command_line;
    gather_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++gathered_;
    pipelines_->deliver(f);
  }

  CatalystConfig config_;
  std::string output_dir_;
  ParcelArraysOf parcels_of_;
  void* handle_ = nullptr;
  std::string module_path_;
  CatalystFactory factory_ = nullptr;
  std::unique_ptr<CatalystPipelines> pipelines_;
  GasCellArrays gas_;  // reused: no reallocation after the first frame
  /// insitu.catalyst.interval (simulated s) or interval_steps.
  Cadence frames_;
  long long gathered_ = 0;
  double gather_seconds_ = 0.0;
};

}  // namespace

std::unique_ptr<Observer> make_catalyst_observer(const Scene& scene, const std::string& output_dir,
                                                 ParcelArraysOf parcels_of) {
  return std::make_unique<CatalystObserver>(scene, output_dir, std::move(parcels_of));
}

}  // namespace dustlift
