#pragma once
// VTK XML writers (inline binary, zlib, UInt64 headers: see docs/output.md for why not
// appended). VTK-free header: VTK is included only in insitu/vtk_*.cpp.
#include <cstddef>
#include <span>
#include <string>

#include "insitu/gas_cells.hpp"
#include "insitu/parcel_arrays.hpp"
#include "insitu/pvd_collection.hpp"

namespace dustlift {

/// Writes a vtkRectilinearGrid (.vtr): nodes from x_nodes/y_nodes (z = 0), cell data
/// density, velocity (3 comp., z = 0), pressure, temperature, mach, alpha_p, vorticity.
void write_gas_vtr(const GasCellArrays& gas, const std::string& path);

/// Writes a vtkPolyData (.vtp): one vertex cell per parcel at (x, y, 0), point data
/// named as the view's members (vectors as 3 components with z = 0).
void write_parcels_vtp(const ParcelArraysView& parcels, const std::string& path);

/// Writes numbered files OUTDIR/vtk/<prefix>_NNNNNN.<ext> and keeps OUTDIR/<prefix>.pvd
/// current. A write at the same time as the previous one overwrites that file.
class VtkSeriesFiles {
 public:
  VtkSeriesFiles(const std::string& output_dir, std::string prefix, std::string extension);
  /// Path to write the dataset of `time` to; call commit() after writing it.
  std::string next_path(double time);
  void commit(double time);
  const PvdCollection& collection() const { return pvd_; }

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
  void write(const ParcelArraysView& parcels, double time);
  const PvdCollection& collection() const { return files_.collection(); }

 private:
  VtkSeriesFiles files_;
};

}  // namespace dustlift
