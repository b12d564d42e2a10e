#include "insitu/provenance_of.hpp"

namespace dustlift {

SeriesSink series_sink_of(const StateView& view) {
  SeriesFileInfo info;
  if (view.provenance != nullptr) {
    info.code_version = view.provenance->code_version;
    info.command_line = view.provenance->command_line;
  }
  if (view.scene != nullptr) info.scene = view.scene->resolved_toml;
  return SeriesSink(view.output_dir, std::move(info));
}

VtkFileInfo vtk_file_info_of(const StateView& view) {
  VtkFileInfo info;
  info.time = view.time;
  if (view.provenance != nullptr) {
    info.code_version = view.provenance->code_version;
    info.command_line = view.provenance->command_line;
  }
  return info;
}

}  // namespace dustlift
