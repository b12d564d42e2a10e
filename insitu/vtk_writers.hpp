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
/// A piece of a decomposed run gives the whole-grid index of its first column.
void write_gas_vtr(const GasCellArrays& gas, const std::string& path, const VtkFileInfo& info = {},
                   int first_column = 0);

/// Writes a vtkPolyData (.vtp): one vertex cell per parcel at (x, y, 0), point data
/// named as the view's members (vectors as 3 components with z = 0) and its extra columns;
/// field data as the .vtr.
void write_parcels_vtp(const ParcelArraysView& parcels, const std::string& path,
                       const VtkFileInfo& info = {});

/// Writes the summary file of a dataset written as one piece per rank (ParaView's parallel
/// XML formats, read like one file): a .pvtr of the rectilinear pieces, whose extents are
/// the whole grid's columns [column_bounds[r], column_bounds[r + 1]) and all rows, the piece
/// files `sources` (relative to the summary's folder, in rank order), and the arrays of
/// `sample` (any rank's piece: every piece holds the same arrays).
void write_gas_pvtr(const GasCellArrays& sample, const std::vector<int>& column_bounds,
                    const std::vector<std::string>& sources, const std::string& path);
/// The same for parcels: a .pvtp listing the pieces `sources` with the point arrays of `sample`.
void write_parcels_pvtp(const ParcelArraysView& sample, const std::vector<std::string>& sources,
                        const std::string& path);

/// Writes numbered files OUTDIR/vtk/<prefix>_NNNNNN.<ext> and keeps OUTDIR/<prefix>.pvd
/// current. A write at the same time as the previous one overwrites that file. Each file is
/// written under a temporary name and renamed when complete (commit), so the .pvd never
/// lists a half-written file, whenever the process is killed.
///
/// A dataset in pieces (a decomposed run) is the summary file <prefix>_NNNNNN.p<ext> that
/// the .pvd lists, beside its pieces <prefix>_NNNNNN_<rank>.<ext>: each rank numbers its
/// files alike, rank 0 alone keeps the .pvd (`lists`).
class VtkSeriesFiles {
 public:
  VtkSeriesFiles(const std::string& output_dir, std::string prefix, std::string extension,
                 bool lists = true);
  /// Path to write the dataset of `time` to (a temporary); call commit() after writing it.
  std::string next_path(double time);
  /// After next_path: the file name of piece `piece` of that dataset, relative to the vtk
  /// folder (the summary's Source), with the extension `piece_extension`.
  std::string piece_name(int piece, const std::string& piece_extension) const;
  /// After next_path: the full path of that piece.
  std::string piece_path(int piece, const std::string& piece_extension) const;
  /// Renames the written file to its numbered name and lists it in the .pvd; without
  /// `lists`, only advances the numbering (the file is another rank's to write).
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
  /// numbered files of this folder that the restored run wrote after its checkpoint (whole
  /// files, summaries and pieces alike: the run may have had another number of ranks).
  /// Without `lists`, only takes the numbering.
  void resume(State state, const std::string& previous_output_dir);

 private:
  std::string output_dir_, prefix_, extension_;
  bool lists_ = true;
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
