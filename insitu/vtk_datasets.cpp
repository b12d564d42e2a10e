#include "insitu/vtk_datasets.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>

#include <utility>

#include "insitu/vtk_writers.hpp"

namespace dustlift {
namespace {

vtkSmartPointer<vtkDoubleArray> copied_array(const char* name, std::span<const double> values) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}

/// Wraps `values` (save = 1: VTK never frees or writes it; the const_cast only satisfies
/// VTK's non-const signature).
vtkSmartPointer<vtkDoubleArray> wrapped_array(const char* name, std::span<const double> values) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetArray(const_cast<double*>(values.data()), static_cast<vtkIdType>(values.size()), 1);
  return a;
}

vtkSmartPointer<vtkDoubleArray> vector_array(const char* name, std::span<const double> x,
                                             std::span<const double> y) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(x.size()));
  double* out = a->GetPointer(0);
  for (std::size_t k = 0; k < x.size(); ++k) {
    out[3 * k] = x[k];
    out[3 * k + 1] = y[k];
    out[3 * k + 2] = 0.0;
  }
  return a;
}

}  // namespace

vtkSmartPointer<vtkRectilinearGrid> make_gas_grid(const GasCellArrays& gas, int first_column) {
  auto grid = vtkSmartPointer<vtkRectilinearGrid>::New();
  grid->SetExtent(first_column, first_column + static_cast<int>(gas.x_nodes.size()) - 1, 0,
                  static_cast<int>(gas.y_nodes.size()) - 1, 0, 0);
  const double z0[1] = {0.0};
  grid->SetXCoordinates(copied_array("x", gas.x_nodes));
  grid->SetYCoordinates(copied_array("y", gas.y_nodes));
  grid->SetZCoordinates(copied_array("z", z0));
  return grid;
}

void set_gas_cell_data(vtkRectilinearGrid* grid, const GasCellArrays& gas) {
  vtkCellData* cd = grid->GetCellData();
  cd->Initialize();
  for (const GasCellArray& a : gas.arrays) {
    if (a.components.size() == 2) {
      cd->AddArray(vector_array(a.name.c_str(), a.components[0], a.components[1]));
    } else {
      cd->AddArray(wrapped_array(a.name.c_str(), a.components.at(0)));
    }
  }
  cd->SetActiveScalars("pressure");
  grid->Modified();
}

vtkSmartPointer<vtkPolyData> make_parcel_polydata(const ParcelArraysView& parcels) {
  const auto n = static_cast<vtkIdType>(parcels.count);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  double* xyz = static_cast<double*>(points->GetVoidPointer(0));
  for (vtkIdType k = 0; k < n; ++k) {
    xyz[3 * k] = parcels.position.x[static_cast<std::size_t>(k)];
    xyz[3 * k + 1] = parcels.position.y[static_cast<std::size_t>(k)];
    xyz[3 * k + 2] = 0.0;
  }
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  for (vtkIdType k = 0; k <= n; ++k) offsets->SetValue(k, k);
  for (vtkIdType k = 0; k < n; ++k) connectivity->SetValue(k, k);
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);

  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetVerts(vertices);
  vtkPointData* pd = poly->GetPointData();
  for (const ParcelPointArray& a : parcels.arrays) {
    if (!is_present(a.x)) continue;
    if (a.is_vector()) {
      pd->AddArray(vector_array(a.name.c_str(), a.x, a.y));
    } else {
      pd->AddArray(wrapped_array(a.name.c_str(), a.x));
    }
  }
  if (parcels.id.data() != nullptr) {
    static_assert(sizeof(int) == sizeof(std::int32_t));
    vtkNew<vtkIntArray> id;
    id->SetName("id");
    id->SetArray(const_cast<int*>(reinterpret_cast<const int*>(parcels.id.data())), n, 1);
    pd->AddArray(id);
  }
  return poly;
}

void add_field_data(vtkDataObject* data, const VtkFileInfo& info) {
  vtkFieldData* fd = data->GetFieldData();
  fd->Initialize();
  const double time[1] = {info.time};
  fd->AddArray(copied_array("TimeValue", time));
  for (const auto& [name, text] : {std::pair{"code_version", &info.code_version},
                                   std::pair{"command_line", &info.command_line}}) {
    vtkNew<vtkStringArray> a;
    a->SetName(name);
    a->InsertNextValue(*text);
    fd->AddArray(a);
  }
}

}  // namespace dustlift
