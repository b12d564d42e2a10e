// VTK side of the writers. Inline binary + zlib: ParaView 5.11 as packaged reads
// appended data as empty with newer libexpat (inline binary reads in every version).
#include "insitu/vtk_writers.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLRectilinearGridWriter.h>
#include <vtkXMLWriter.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "insitu/vtk_datasets.hpp"

namespace dustlift {
namespace {

void configure_binary_zlib(vtkXMLWriter* writer, const std::string& path) {
  writer->SetFileName(path.c_str());
  writer->SetDataModeToBinary();  // inline binary (base64) inside the XML
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();
  // Fastest zlib level: deflate + base64 dominate the output time (~1.5 s for 360k cells
  // of 8 arrays on a loaded 2-core machine); level 5 was ~25 % slower for ~0.1 % less disk.
  writer->SetCompressionLevel(1);
}

void prepare_folder(const std::string& path) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
}

}  // namespace

void write_gas_vtr(const GasCellArrays& gas, const std::string& path, const VtkFileInfo& info,
                   int first_column) {
  gas.check_sizes();
  if (gas.cells() == 0) throw std::invalid_argument("write_gas_vtr: empty grid");
  vtkSmartPointer<vtkRectilinearGrid> grid = make_gas_grid(gas, first_column);
  set_gas_cell_data(grid, gas);
  add_field_data(grid, info);

  prepare_folder(path);
  vtkNew<vtkXMLRectilinearGridWriter> writer;
  configure_binary_zlib(writer, path);
  writer->SetInputData(grid);
  if (writer->Write() != 1) throw std::runtime_error("VTK could not write " + path);
}

void write_parcels_vtp(const ParcelArraysView& parcels, const std::string& path,
                       const VtkFileInfo& info) {
  parcels.check_sizes();
  vtkSmartPointer<vtkPolyData> poly = make_parcel_polydata(parcels);
  add_field_data(poly, info);

  prepare_folder(path);
  vtkNew<vtkXMLPolyDataWriter> writer;
  configure_binary_zlib(writer, path);
  writer->SetInputData(poly);
  if (writer->Write() != 1) throw std::runtime_error("VTK could not write " + path);
}

namespace {

/// The XML name of a VTK array's value type, as the serial writers put it in the pieces.
const char* xml_type_name(vtkAbstractArray& a) {
  switch (a.GetDataType()) {
    case VTK_DOUBLE:
      return "Float64";
    case VTK_FLOAT:
      return "Float32";
    case VTK_INT:
      return "Int32";
    case VTK_ID_TYPE:
      return sizeof(vtkIdType) == 8 ? "Int64" : "Int32";
    case VTK_LONG_LONG:
      return "Int64";
    case VTK_UNSIGNED_CHAR:
      return "UInt8";
    case VTK_STRING:
      return "String";
    default:
      throw std::logic_error(std::string("no XML type name for VTK array ") + a.GetName());
  }
}

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// <PDataArray .../> lines of every array of `data` (point or cell data).
void list_arrays(std::ostream& out, vtkDataSetAttributes* data, const char* indent) {
  for (int k = 0; k < data->GetNumberOfArrays(); ++k) {
    vtkAbstractArray& a = *data->GetAbstractArray(k);
    out << indent << "<PDataArray type=\"" << xml_type_name(a) << "\" Name=\""
        << xml_escaped(a.GetName()) << "\"";
    if (a.GetNumberOfComponents() != 1)
      out << " NumberOfComponents=\"" << a.GetNumberOfComponents() << "\"";
    out << "/>\n";
  }
}

void write_text_file(const std::string& path, const std::string& text) {
  prepare_folder(path);
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
  f.close();
  if (!f) throw std::runtime_error("could not write " + path);
}

std::string header(const char* type) {
  static_assert(std::endian::native == std::endian::little, "the pieces are written little-endian");
  return std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"") + type +
         "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
}

}  // namespace

void write_gas_pvtr(const GasCellArrays& sample, const std::vector<int>& column_bounds,
                    const std::vector<std::string>& sources, const std::string& path) {
  if (column_bounds.size() != sources.size() + 1 || sources.empty())
    throw std::invalid_argument("write_gas_pvtr: one source per slab");
  vtkSmartPointer<vtkRectilinearGrid> grid = make_gas_grid(sample);
  set_gas_cell_data(grid, sample);
  const std::size_t rows = sample.ny();
  std::ostringstream out;
  out << header("PRectilinearGrid") << "  <PRectilinearGrid WholeExtent=\"0 "
      << column_bounds.back() << " 0 " << rows << " 0 0\" GhostLevel=\"0\">\n"
      << "    <PCellData Scalars=\"pressure\">\n";
  list_arrays(out, grid->GetCellData(), "      ");
  out << "    </PCellData>\n    <PCoordinates>\n";
  for (vtkDataArray* c :
       {grid->GetXCoordinates(), grid->GetYCoordinates(), grid->GetZCoordinates()}) {
    out << "      <PDataArray type=\"" << xml_type_name(*c) << "\" Name=\"" << c->GetName()
        << "\"/>\n";
  }
  out << "    </PCoordinates>\n";
  for (std::size_t r = 0; r < sources.size(); ++r) {
    out << "    <Piece Extent=\"" << column_bounds[r] << " " << column_bounds[r + 1] << " 0 "
        << rows << " 0 0\" Source=\"" << xml_escaped(sources[r]) << "\"/>\n";
  }
  out << "  </PRectilinearGrid>\n</VTKFile>\n";
  write_text_file(path, out.str());
}

void write_parcels_pvtp(const ParcelArraysView& sample, const std::vector<std::string>& sources,
                        const std::string& path) {
  vtkSmartPointer<vtkPolyData> poly = make_parcel_polydata(sample);
  std::ostringstream out;
  out << header("PPolyData") << "  <PPolyData GhostLevel=\"0\">\n    <PPointData>\n";
  list_arrays(out, poly->GetPointData(), "      ");
  out << "    </PPointData>\n    <PPoints>\n"
      << "      <PDataArray type=\"" << xml_type_name(*poly->GetPoints()->GetData())
      << "\" Name=\"Points\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
  for (const std::string& source : sources)
    out << "    <Piece Source=\"" << xml_escaped(source) << "\"/>\n";
  out << "  </PPolyData>\n</VTKFile>\n";
  write_text_file(path, out.str());
}

VtkSeriesFiles::VtkSeriesFiles(const std::string& output_dir, std::string prefix,
                               std::string extension, bool lists)
    : output_dir_(output_dir),
      prefix_(std::move(prefix)),
      extension_(std::move(extension)),
      lists_(lists),
      pvd_((std::filesystem::path(output_dir) / (prefix_ + ".pvd")).string()) {}

std::string VtkSeriesFiles::piece_name(int piece, const std::string& piece_extension) const {
  if (pending_.empty()) throw std::logic_error("VtkSeriesFiles::piece_name without next_path");
  const std::filesystem::path summary(pending_);
  return summary.stem().string() + "_" + std::to_string(piece) + "." + piece_extension;
}

std::string VtkSeriesFiles::piece_path(int piece, const std::string& piece_extension) const {
  return (std::filesystem::path(output_dir_) / "vtk" / piece_name(piece, piece_extension)).string();
}

std::string VtkSeriesFiles::next_path(double time) {
  const bool same_time = has_last_ && time == last_time_;
  const long long index = same_time ? next_index_ - 1 : next_index_;
  pending_ =
      (std::filesystem::path("vtk") / numbered_file_name(prefix_, index, extension_)).string();
  return (std::filesystem::path(output_dir_) / pending_).string() + ".tmp";
}

void VtkSeriesFiles::commit(double time) {
  if (pending_.empty()) throw std::logic_error("VtkSeriesFiles::commit without next_path");
  const bool same_time = has_last_ && time == last_time_;
  if (lists_) {
    const std::filesystem::path target = std::filesystem::path(output_dir_) / pending_;
    std::filesystem::rename(target.string() + ".tmp", target);
    pvd_.add(time, pending_);
  }
  if (!same_time) ++next_index_;
  has_last_ = true;
  last_time_ = time;
  pending_.clear();
}

void VtkSeriesFiles::save_state(Snapshot& s, const std::string& prefix) const {
  std::vector<double> times;
  std::string files;
  for (const auto& e : pvd_.entries()) {
    times.push_back(e.time);
    files += (files.empty() ? "" : "\n") + e.file;
  }
  s.f64[prefix + "times"] = times;
  s.text[prefix + "files"] = files;
  s.i64[prefix + "next_index"] = {next_index_};
  s.f64[prefix + "last_time"] = {has_last_ ? last_time_ : std::numeric_limits<double>::quiet_NaN()};
}

VtkSeriesFiles::State VtkSeriesFiles::read_state(const Snapshot& s, const std::string& prefix) {
  const auto& times = snapshot_array(s.f64, prefix + "times");
  const std::string& files = snapshot_text(s, prefix + "files");
  std::vector<PvdCollection::Entry> entries;
  std::size_t start = 0;
  for (double t : times) {
    if (start > files.size())
      throw SnapshotError("text '" + prefix + "files' lists fewer files than times");
    const std::size_t end = std::min(files.find('\n', start), files.size());
    entries.push_back({t, files.substr(start, end - start)});
    start = end + 1;
  }
  const long long next = snapshot_array(s.i64, prefix + "next_index", 1)[0];
  if (next < 0) throw SnapshotError("array '" + prefix + "next_index' is negative");
  const double last = snapshot_array(s.f64, prefix + "last_time", 1)[0];
  return State{std::move(entries), next, !std::isnan(last), std::isnan(last) ? 0.0 : last};
}

void VtkSeriesFiles::resume(State state, const std::string& previous_output_dir) {
  next_index_ = state.next_index;
  has_last_ = state.has_last;
  last_time_ = state.last_time;
  if (!lists_) return;
  namespace fs = std::filesystem;
  const fs::path here = fs::absolute(output_dir_).lexically_normal();
  std::error_code ec;
  const bool elsewhere =
      !previous_output_dir.empty() && !fs::equivalent(previous_output_dir, output_dir_, ec);
  std::vector<PvdCollection::Entry> entries = std::move(state.entries);
  if (elsewhere) {
    const fs::path there = fs::absolute(previous_output_dir).lexically_normal();
    for (auto& e : entries) {
      if (fs::path(e.file).is_relative())
        e.file = (there / e.file).lexically_normal().lexically_relative(here).string();
    }
  }
  pvd_.assign(std::move(entries));
  // Files this folder holds beyond the checkpoint (written by the run after it; or .tmp of an
  // interrupted write) would be listed by nothing: remove them.
  const fs::path folder = here / "vtk";
  if (!fs::is_directory(folder, ec)) return;
  // The whole file's extension, a summary's ("p" + it) and its pieces' (_<rank> + it).
  const std::string whole =
      extension_.size() > 1 && extension_[0] == 'p' ? extension_.substr(1) : extension_;
  const auto is_numbered_rest = [&](std::string rest) {
    if (rest.size() > 4 && rest.compare(rest.size() - 4, 4, ".tmp") == 0)
      rest.resize(rest.size() - 4);
    if (rest == "." + whole || rest == ".p" + whole) return true;
    const std::size_t dot = rest.find('.');
    return rest.size() > 2 && rest[0] == '_' && dot != std::string::npos && dot > 1 &&
           rest.find_first_not_of("0123456789", 1) == dot && rest.substr(dot) == "." + whole;
  };
  const std::string head = prefix_ + "_";
  std::vector<fs::path> stale;
  for (const auto& f : fs::directory_iterator(folder, ec)) {
    const std::string name = f.path().filename().string();
    if (name.rfind(head, 0) != 0) continue;
    const std::string digits = name.substr(head.size(), 6);
    if (digits.size() != 6 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string rest = name.substr(head.size() + 6);
    if (!is_numbered_rest(rest)) continue;
    const bool temporary = rest.size() > 4 && rest.compare(rest.size() - 4, 4, ".tmp") == 0;
    if (std::stoll(digits) >= next_index_ || temporary) stale.push_back(f.path());
  }
  for (const auto& f : stale) fs::remove(f, ec);
}

ParcelSeriesWriter::ParcelSeriesWriter(const std::string& output_dir)
    : files_(output_dir, "parcels", "vtp") {}

void ParcelSeriesWriter::write(const ParcelArraysView& parcels, double time,
                               const VtkFileInfo& info) {
  write_parcels_vtp(parcels, files_.next_path(time), info);
  files_.commit(time);
}

}  // namespace dustlift
