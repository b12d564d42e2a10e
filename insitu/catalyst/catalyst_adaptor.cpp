// The ParaView Catalyst adaptor (legacy vtkCP API of ParaView 5.11, the one Debian packages;
// Catalyst 2 / conduit is not packaged). Built as the module libdustlift_catalyst.so and
// loaded by insitu/catalyst_observer.cpp only when a scene asks for it.
//
// Channels: "gas", a vtkRectilinearGrid whose structure is built once and whose scalar cell
// arrays wrap the observer's gathered arrays; "parcels", a vtkPolyData whose scalar point
// arrays wrap the parcel system's columns. Both carry the same arrays as the .vtr/.vtp
// (insitu/vtk_datasets.cpp builds them for both).
#include "insitu/catalyst_adaptor.hpp"

#include <fmt/format.h>
#ifdef DUSTLIFT_CATALYST_WITH_MPI
#include <mpi.h>
#include <vtkMPI.h>  // vtkMPICommunicatorOpaqueComm
#endif
#include <vtkCPDataDescription.h>
#include <vtkCPInputDataDescription.h>
#include <vtkCPProcessor.h>
#include <vtkCPPythonPipeline.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "insitu/catalyst/virtual_display.hpp"
#include "insitu/vtk_datasets.hpp"
#include "insitu/vtk_writers.hpp"

namespace dustlift {
namespace {

/// Sends what VTK and the embedded Python print (Python's stdout/stderr are redirected to the
/// output window) to the run's log, one line at a time, each prefixed "catalyst: ".
class LogWindow : public vtkOutputWindow {
 public:
  static LogWindow* New();
  vtkTypeMacro(LogWindow, vtkOutputWindow);
  void set_log(std::function<void(const std::string&)> log) { log_ = std::move(log); }
  void DisplayText(const char* text) override {
    if (text == nullptr) return;
    pending_ += text;
    std::size_t nl;
    while ((nl = pending_.find('\n')) != std::string::npos) {
      emit(pending_.substr(0, nl));
      pending_.erase(0, nl + 1);
    }
  }
  void flush() {
    if (!pending_.empty()) emit(pending_);
    pending_.clear();
  }

 private:
  void emit(const std::string& line) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) return;
    // ParaView's trivial producer starts at time 0, so the first frame (t = 0) draws this
    // warning once per channel; it says nothing about the run.
    if (line.find("New time step is not after last time step") != std::string::npos ||
        line.find("Warning: In vtkPVTrivialProducer.cxx") != std::string::npos)
      return;
    if (log_) log_("catalyst: " + line);
  }
  std::function<void(const std::string&)> log_;
  std::string pending_;
};
vtkStandardNewMacro(LogWindow);

/// The built-in Live pipeline: the two channels, published to the GUI at every delivery.
std::string live_script(const std::string& url) {
  return fmt::format(R"(# script-version: 2
# Written by dustlift for [insitu.catalyst] live = true: publishes the channels to ParaView Live.
# In the GUI: Catalyst > Connect (port {1}), then click the channels in the Catalyst browser.
from paraview.simple import *
from paraview import catalyst
gas = TrivialProducer(registrationName='gas')
parcels = TrivialProducer(registrationName='parcels')
options = catalyst.Options()
options.EnableCatalystLive = 1
options.CatalystLiveURL = '{0}'
)",
                     url, url.substr(url.rfind(':') + 1));
}

class CatalystAdaptor final : public CatalystPipelines {
 public:
  explicit CatalystAdaptor(const CatalystSettings& s) : settings_(s) {
    if (std::getenv("DISPLAY") == nullptr || *std::getenv("DISPLAY") == '\0') display_.emplace();
    // ParaView's loguru sink still prints its warnings on stderr too: turning it off
    // (SetStderrVerbosity) breaks ParaView 5.11's Python log handler, which then fails on
    // every message of the catalyst package.
    window_->set_log(settings_.log);
    vtkOutputWindow::SetInstance(window_);
    initialize_processor();
    vtkOutputWindow::SetInstance(window_);  // ParaView's initialisation installs its own
    if (display_)
      log(fmt::format("catalyst: no DISPLAY: renders go to a private Xvfb on {} (Mesa llvmpipe)",
                      display_->display()));
    std::vector<std::string> scripts = settings_.scripts;
    if (settings_.live) {
      const std::string path =
          (std::filesystem::path(settings_.output_dir) / "catalyst_live.py").string();
      std::ofstream(path) << live_script(settings_.live_url);
      scripts.push_back(path);
    }
    for (const auto& script : scripts) {
      vtkSmartPointer<vtkCPPythonPipeline> p =
          vtkCPPythonPipeline::CreateAndInitializePipeline(script.c_str());
      window_->flush();
      if (!p) {
        log("catalyst: " + script +
            " did not load (see the lines above); the run goes on without it");
        continue;
      }
      processor_->AddPipeline(p);
      log(fmt::format("catalyst: pipeline {} (script version {})", script,
                      vtkCPPythonPipeline::DetectScriptVersion(script.c_str())));
    }
  }

  ~CatalystAdaptor() override { finalize(); }

 private:
  /// Under mpirun the pipelines run on rank 0 alone, on the state gathered there: ParaView is
  /// set up on that rank's own communicator, since on MPI_COMM_WORLD its set-up is a collective
  /// the other ranks, busy with the run, never join (the run hung there).
  void initialize_processor() {
#ifdef DUSTLIFT_CATALYST_WITH_MPI
    int mpi_started = 0;
    MPI_Initialized(&mpi_started);
    if (mpi_started != 0) {
      vtkMPICommunicatorOpaqueComm own(&own_communicator_);
      processor_->Initialize(own, settings_.output_dir.c_str());
      return;
    }
#endif
    processor_->Initialize(settings_.output_dir.c_str());
  }

 public:
  bool wants(double time, long long step, bool last) override {
    if (finalized_) return false;
    description_->ResetAll();
    description_->AddInput("gas");
    description_->AddInput("parcels");
    description_->SetTimeData(time, static_cast<vtkIdType>(step));
    description_->SetForceOutput(last);
    return processor_->RequestDataDescription(description_) != 0;
  }

  void deliver(const CatalystFrame& f) override {
    if (finalized_ || f.gas == nullptr) return;
    const auto t0 = std::chrono::steady_clock::now();
    const VtkFileInfo info{f.time, f.code_version, f.command_line};
    if (!grid_ || grid_nx_ != f.gas->nx() || grid_ny_ != f.gas->ny()) {
      grid_ = make_gas_grid(*f.gas);  // the structure once (again only if the grid changed)
      grid_nx_ = f.gas->nx();
      grid_ny_ = f.gas->ny();
    }
    set_gas_cell_data(grid_, *f.gas);
    add_field_data(grid_, info);
    description_->GetInputDescriptionByName("gas")->SetGrid(grid_);
    if (f.parcels != nullptr) {
      vtkSmartPointer<vtkPolyData> parcels = make_parcel_polydata(*f.parcels);
      add_field_data(parcels, info);
      description_->GetInputDescriptionByName("parcels")->SetGrid(parcels);
    } else {
      description_->GetInputDescriptionByName("parcels")->SetGrid(empty_parcels_);
    }
    const int ok = processor_->CoProcess(description_);
    window_->flush();
    if (ok == 0) {
      ++failures_;
      log(fmt::format("catalyst: a pipeline failed at step {} (t = {:.6e} s); the run goes on",
                      f.step, f.time));
    }
    // Drop the wrapped arrays now: they point into memory the solver changes.
    description_->GetInputDescriptionByName("gas")->SetGrid(nullptr);
    description_->GetInputDescriptionByName("parcels")->SetGrid(nullptr);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++deliveries_;
  }

  void finalize() override {
    if (finalized_) return;
    finalized_ = true;
    processor_->Finalize();
    window_->flush();
    log(fmt::format(
        "catalyst: {} deliveries, {:.3f} s in the pipelines ({:.2f} ms each), {} failed",
        deliveries_, seconds_,
        deliveries_ > 0 ? 1e3 * seconds_ / static_cast<double>(deliveries_) : 0.0, failures_));
    vtkOutputWindow::SetInstance(nullptr);
  }

 private:
  void log(const std::string& line) {
    if (settings_.log) settings_.log(line);
  }

  CatalystSettings settings_;
  std::optional<VirtualDisplay> display_;  // before the processor: it must outlive rendering
  vtkNew<LogWindow> window_;
#ifdef DUSTLIFT_CATALYST_WITH_MPI
  MPI_Comm own_communicator_ = MPI_COMM_SELF;
#endif
  vtkNew<vtkCPProcessor> processor_;
  vtkNew<vtkCPDataDescription> description_;
  vtkSmartPointer<vtkRectilinearGrid> grid_;
  vtkNew<vtkPolyData> empty_parcels_;
  std::size_t grid_nx_ = 0, grid_ny_ = 0;
  long long deliveries_ = 0, failures_ = 0;
  double seconds_ = 0.0;
  bool finalized_ = false;
};

}  // namespace
}  // namespace dustlift

extern "C" __attribute__((visibility("default"))) dustlift::CatalystPipelines*
dustlift_catalyst_create(const dustlift::CatalystSettings& settings, std::string& error) {
  try {
    return new dustlift::CatalystAdaptor(settings);
  } catch (const std::exception& e) {
    error = e.what();
    return nullptr;
  }
}
