#pragma once
// The VTK datasets of the gas and parcel outputs, built once for the .vtr/.vtp writers and the
// Catalyst channels, so that both hold the same arrays under the same names (docs/output.md).
// Includes VTK: only for insitu/ sources that already depend on VTK, never solver headers.
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>

#include "insitu/gas_cells.hpp"
#include "insitu/parcel_arrays.hpp"

namespace dustlift {

struct VtkFileInfo;

/// A rectilinear grid with the nodes of `gas` (z = 0) and no cell data. A piece of a
/// decomposed run has the extent of its columns in the whole grid, starting at
/// `first_column` (ParaView's .pvtr reader places the pieces by their extents).
vtkSmartPointer<vtkRectilinearGrid> make_gas_grid(const GasCellArrays& gas, int first_column = 0);

/// Replaces the cell data of `grid` by the arrays of `gas` in their order (gas_fields();
/// vectors with z = 0; active scalars pressure). The scalar
/// arrays wrap `gas`'s storage without a copy: `gas` must outlive their use and not be
/// resized meanwhile. The velocity is interleaved into a new 3-component array.
void set_gas_cell_data(vtkRectilinearGrid* grid, const GasCellArrays& gas);

/// One vertex cell per parcel at (x, y, 0) with every array of `parcels` (vectors as three
/// components, z = 0) and `id`. Scalar columns wrap the parcel arrays without a copy (valid
/// until the parcel system next changes them); positions and vectors are interleaved copies.
vtkSmartPointer<vtkPolyData> make_parcel_polydata(const ParcelArraysView& parcels);

/// Field data TimeValue (ParaView reads it as the time), code_version and command_line.
void add_field_data(vtkDataObject* data, const VtkFileInfo& info);

}  // namespace dustlift
