#pragma once
// What the output files of a run record about it, as an observer sees the run: the series
// sink (output folder; code version, command line and resolved scene for series.h5) and the
// VTK field data (time, code version, command line).
#include "insitu/series_table.hpp"
#include "insitu/vtk_writers.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

SeriesSink series_sink_of(const StateView& view);
VtkFileInfo vtk_file_info_of(const StateView& view);

}  // namespace dustlift
