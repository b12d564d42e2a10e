#pragma once
// VTK XML writers (inline binary, zlib, UInt64 headers: see docs/output.md for why not
// appended). VTK-free header: VTK is included only in insitu/vtk_*.cpp.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "insitu/gas_cells.hpp"
#include "insitu/parcel_arrays.hpp"
#include "insitu/pvd_collection.hpp"
#include "solver/sim/snapshot.hpp"

namespace dustlift {

/// Field data of a VTK file: what it is (simulated time; ParaView reads TimeValue) and how it
/// was made.
struct VtkFileInfo {
  double time = 0.0;  ///< s
  std::string code_version, command_line;
};

/// Writes a vtkRectilinearGrid (.vtr): nodes from x_nodes/y_nodes (z = 0), cell data
/// density, velocity (3 comp., z = 0), pressure, temperature, mach, alpha_p, vorticity;
/// field data TimeValue, code_version, command_line.
void write_gas_vtr(const GasCellArrays& gas, const std::string& path, const VtkFileInfo& info = {});

/// Writes a vtkPolyData (.vtp): one vertex cell per parcel at (x, y, 0), point data
/// named as the view's members (vectors as 3 components with z = 0) and its extra columns;
/// field data as the .vtr.
void write_parcels_vtp(const ParcelArraysView& parcels, const std::string& path, const VtkFileInfo& info = {});

/// Writes numbered files OUTDIR/vtk/<prefix>_NNNNNN.<ext> and keeps OUTDIR/<prefix>.pvd
/// current. A write at the same time as the previous one overwrites that file. Each file is
/// written under a temporary name and renamed when complete (commit), so the .pvd never
/// lists a half-written file, whenever the process is killed.
class VtkSeriesFiles {
 public:
  VtkSeriesFiles(const std::string& output_dir, std::string prefix, std::string extension);
  /// Path to write the dataset of `time` to (a temporary); call commit() after writing it.
  std::string next_path(double time);
  /// Renames the written file to its numbered name and lists it in the .pvd.
  void commit(double time);
  const PvdCollection& collection() const { return pvd_; }
  /// Whether the last committed file holds `time` (an output repeated at the same time).
  bool last_time_is(double time) const { return has_last_ && time == last_time_; }

  /// Checkpoint state: the .pvd entries, the next file number and the last time.
  struct State {
    std::vector<PvdCollection::Entry> entries;
    long long next_index = 0;
    bool has_last = false;
    double last_time = 0.0;
  };
  void save_state(Snapshot& s, const std::string& prefix) const;
  /// Reads a State saved under `prefix`; SnapshotError naming the array when it does not fit.
  static State read_state(const Snapshot& s, const std::string& prefix);
  /// Continues from `state`: rewrites the .pvd with exactly its entries (named relative to
  /// this folder when they were written into another, `previous_output_dir`) and removes the
  /// numbered files of this folder that the restored run wrote after its checkpoint.
  void resume(State state, const std::string& previous_output_dir);

 private:
  std::string output_dir_, prefix_, extension_;
  PvdCollection pvd_;
  long long next_index_ = 0;
  std::string pending_;
  bool has_last_ = false;
  double last_time_ = 0.0;
};

/// Parcel series for the lead's ParcelSystem observer: parcels_NNNNNN.vtp + parcels.pvd.
class ParcelSeriesWriter {
 public:
  explicit ParcelSeriesWriter(const std::string& output_dir);
  void write(const ParcelArraysView& parcels, double time, const VtkFileInfo& info = {});
  const PvdCollection& collection() const { return files_.collection(); }
  VtkSeriesFiles& files() { return files_; }
  const VtkSeriesFiles& files() const { return files_; }

 private:
  VtkSeriesFiles files_;
};

}  // namespace dustlift
