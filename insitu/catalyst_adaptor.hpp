#pragma once
// The interface between dustlift and its ParaView Catalyst adaptor (docs/catalyst.md).
// VTK-free: the adaptor itself (insitu/catalyst/catalyst_adaptor.cpp) is a module,
// libdustlift_catalyst.so, that the Catalyst observer loads only when a scene has an
// [insitu.catalyst] section, so a run without one neither loads ParaView nor starts Python.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "insitu/gas_cells.hpp"
#include "insitu/parcel_arrays.hpp"

namespace dustlift {

struct CatalystSettings {
  std::vector<std::string>
      scripts;             ///< Catalyst Python scripts (v1, or v2 with "# script-version: 2")
  bool live = false;       ///< add a pipeline that connects to ParaView Live
  std::string live_url;    ///< host:port of the GUI's Catalyst > Connect
  std::string output_dir;  ///< the run's folder: working directory of the pipelines
  /// Receives each line of text the pipelines print (Python output, tracebacks, VTK warnings).
  std::function<void(const std::string&)> log;
};

/// One delivery: the state of one step. `parcels` is null in a gas-only scene.
struct CatalystFrame {
  double time = 0.0;  ///< s
  long long step = 0;
  bool last =
      false;  ///< the run's last step: every pipeline runs (vtkCPDataDescription ForceOutput)
  const GasCellArrays* gas = nullptr;
  const ParcelArraysView* parcels = nullptr;
  std::string code_version, command_line;
};

/// The adaptor: the two channels "gas" (vtkRectilinearGrid, the .vtr's cell arrays) and
/// "parcels" (vtkPolyData, the .vtp's point arrays with id).
class CatalystPipelines {
 public:
  virtual ~CatalystPipelines() = default;
  /// Whether any pipeline wants this step (a frame is gathered only then).
  virtual bool wants(double time, long long step, bool last) = 0;
  /// Runs the pipelines on the frame; a failing script is logged, never thrown.
  virtual void deliver(const CatalystFrame& frame) = 0;
  /// Ends the pipelines (writes what they hold back); also done by the destructor.
  virtual void finalize() = 0;
};

/// Name of the module's factory, of type CatalystFactory.
inline constexpr const char* kCatalystFactorySymbol = "dustlift_catalyst_create";
/// Creates the adaptor, or returns null with `error` set (e.g. a script that does not load).
using CatalystFactory = CatalystPipelines* (*)(const CatalystSettings& settings,
                                               std::string& error);

}  // namespace dustlift
