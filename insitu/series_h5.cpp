// HDF5 side of SeriesSink (C API). Layout: /<series>/<column> 1-D float64 datasets,
// chunked and extendible, each with a string attribute "units"; the first column is the
// dimension scale of the others (h5py: f["shock_position/x"].dims[0][0] is the time); the
// group carries "columns" (the column names, comma-separated, in order). Root attributes
// record the code version, command line, resolved scene and when the file was written.
// Strings are variable-length UTF-8 (h5py reads them as str).
#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "insitu/hdf5_handle.hpp"
#include "insitu/series_table.hpp"

namespace dustlift {
namespace {

/// The series' errors: std::runtime_error, "HDF5: " and what was being done.
struct SeriesH5Error : std::runtime_error {
  explicit SeriesH5Error(const std::string& what) : std::runtime_error("HDF5: " + what) {}
};
using Handle = Hdf5Handle<SeriesH5Error>;
constexpr auto check = hdf5_check<SeriesH5Error>;

/// A variable-length UTF-8 string type (for attributes of any length).
hid_t utf8_string_type() {
  const hid_t type = H5Tcopy(H5T_C_S1);
  if (type >= 0) {
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
  }
  return type;
}

std::string read_string_attribute(hid_t object, const char* name);

/// Sets a string attribute, stored variable-length; rewritten only when the value changes (a
/// rewritten variable-length string takes new space in the file, never given back).
void write_string_attribute(hid_t object, const char* name, const std::string& value) {
  if (H5Aexists(object, name) > 0) {
    if (read_string_attribute(object, name) == value) return;
    check(H5Adelete(object, name), "delete attribute");
  }
  Handle type(utf8_string_type(), H5Tclose, "string type");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  const char* text = value.c_str();
  check(H5Awrite(attr, type, &text), "write attribute");
}

/// A string attribute that changes at every write (the time written): fixed-length and
/// overwritten in place, so the file does not grow.
void write_fixed_string_attribute(hid_t object, const char* name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, value.size()), "string size");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string pad");
  if (H5Aexists(object, name) > 0) {
    bool same_type = false;
    {
      Handle attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose,
                  std::string("open attribute ") + name);
      Handle stored(H5Aget_type(attr), H5Tclose, "attribute type");
      same_type = H5Tequal(stored, type) > 0;
      if (same_type) check(H5Awrite(attr, type, value.data()), "write attribute");
    }
    if (same_type) return;
    check(H5Adelete(object, name), "delete attribute");
  }
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  check(H5Awrite(attr, type, value.data()), "write attribute");
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

/// Opens the file read-write; creates it when missing or not a readable HDF5 file
/// (e.g. truncated by a killed run: every table is rewritten whole, so nothing is lost
/// that the next writes do not restore).
hid_t open_or_create(const std::string& path) {
  if (std::filesystem::exists(path)) {
    const hid_t file = [&] {
      QuietHdf5 quiet;
      return H5Fis_hdf5(path.c_str()) > 0 ? H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)
                                          : H5I_INVALID_HID;
    }();
    if (file >= 0) return file;
  }
  return H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
}

/// Writes `values` as dataset `name` of `group`; its first `unchanged` rows are already in the
/// file (as far as the dataset reaches), so only the rest is written.
void write_column(hid_t group, const std::string& name, const std::string& unit,
                  const std::vector<double>& values, std::size_t unchanged) {
  const hsize_t rows = values.size();
  if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0) {
    const hsize_t initial = 0, unlimited = H5S_UNLIMITED, chunk = 1024;
    Handle space(H5Screate_simple(1, &initial, &unlimited), H5Sclose, "column space");
    Handle props(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset properties");
    check(H5Pset_chunk(props, 1, &chunk), "chunk");
    Handle created(
        H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, props, H5P_DEFAULT),
        H5Dclose, "create dataset " + name);
    write_string_attribute(created, "units", unit);
  }
  Handle dataset(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  hsize_t extent = 0;
  {
    Handle old_space(H5Dget_space(dataset), H5Sclose, "dataset space");
    check(H5Sget_simple_extent_dims(old_space, &extent, nullptr), "dataset extent " + name);
  }
  // Rewriting a long table whole at every output costs the square of its length over a run.
  const hsize_t first = std::min<hsize_t>({static_cast<hsize_t>(unchanged), extent, rows});
  check(H5Dset_extent(dataset, &rows), "resize dataset " + name);
  const hsize_t count = rows - first;
  if (count == 0) return;
  Handle file_space(H5Dget_space(dataset), H5Sclose, "dataset space");
  check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, &first, nullptr, &count, nullptr),
        "select rows of " + name);
  Handle memory_space(H5Screate_simple(1, &count, nullptr), H5Sclose, "memory space");
  check(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, memory_space, file_space, H5P_DEFAULT,
                 values.data() + first),
        "write dataset " + name);
}

std::string read_string_attribute(hid_t object, const char* name) {
  Handle attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
  if (H5Tis_variable_str(type) > 0) {
    Handle memory(utf8_string_type(), H5Tclose, "string type");
    char* text = nullptr;
    check(H5Aread(attr, memory, &text), std::string("read attribute ") + name);
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  std::string value(H5Tget_size(type), '\0');
  check(H5Aread(attr, type, value.data()), std::string("read attribute ") + name);
  value.erase(value.find_last_not_of('\0') + 1);
  return value;
}

/// The comma-separated list of an attribute.
std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    parts.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return parts;
}

}  // namespace

SeriesTable read_series_h5(const std::string& path, const std::string& name) {
  if (!std::filesystem::exists(path)) throw std::runtime_error("no series file " + path);
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + path);
  const std::string group_path = std::string("/").append(name);
  if (H5Lexists(file, group_path.c_str(), H5P_DEFAULT) <= 0)
    throw std::runtime_error("no series " + name + " in " + path);
  Handle group(H5Gopen2(file, group_path.c_str(), H5P_DEFAULT), H5Gclose,
               "open group " + name + " in " + path);
  // Column order from "columns"; units from the datasets.
  std::vector<SeriesColumn> columns;
  std::vector<std::vector<double>> values;
  for (const std::string& column : split_commas(read_string_attribute(group, "columns"))) {
    if (H5Lexists(group, column.c_str(), H5P_DEFAULT) <= 0)
      throw std::runtime_error("series " + name + ": no dataset for column " + column);
    Handle dataset(H5Dopen2(group, column.c_str(), H5P_DEFAULT), H5Dclose, "open " + column);
    Handle space(H5Dget_space(dataset), H5Sclose, "dataset space");
    const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
    std::vector<double> v(n);
    if (n)
      check(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
            "read " + column);
    columns.push_back({column, read_string_attribute(dataset, "units")});
    values.push_back(std::move(v));
  }
  SeriesTable table(name, columns);
  const std::size_t rows = values.empty() ? 0 : values.front().size();
  std::vector<double> row(columns.size());
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) row[c] = values[c].at(r);
    table.append_row(row);
  }
  return table;
}

void write_series_h5(const std::string& path, const SeriesTable& table, const SeriesFileInfo* info,
                     std::size_t unchanged_rows) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  Handle file(open_or_create(path), H5Fclose, "open or create " + path);
  const std::string group_name = "/" + table.name();
  std::string names;
  for (const auto& c : table.columns()) names.append(names.empty() ? "" : ",").append(c.name);
  // A group written with other columns (e.g. other stations) is replaced whole.
  if (H5Lexists(file, group_name.c_str(), H5P_DEFAULT) > 0) {
    bool same_columns = false;
    {
      Handle group(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT), H5Gclose, "open group");
      same_columns =
          H5Aexists(group, "columns") > 0 && read_string_attribute(group, "columns") == names;
    }
    if (!same_columns) check(H5Ldelete(file, group_name.c_str(), H5P_DEFAULT), "delete group");
  }
  const bool created = H5Lexists(file, group_name.c_str(), H5P_DEFAULT) <= 0;
  if (created) {
    Handle group(H5Gcreate2(file, group_name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Gclose, "create group " + group_name);
    write_string_attribute(group, "columns", names);
  }
  Handle group(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT), H5Gclose, "open group");
  for (std::size_t k = 0; k < table.columns().size(); ++k)
    write_column(group, table.columns()[k].name, table.columns()[k].unit, table.column(k),
                 created ? 0 : unchanged_rows);
  if (created && table.columns().size() > 1) {
    // The abscissa as the dimension scale of every other column.
    const std::string abscissa = table.columns().front().name;
    Handle scale(H5Dopen2(group, abscissa.c_str(), H5P_DEFAULT), H5Dclose, "open " + abscissa);
    check(H5DSset_scale(scale, abscissa.c_str()), "dimension scale " + abscissa);
    for (std::size_t k = 1; k < table.columns().size(); ++k) {
      const std::string& column = table.columns()[k].name;
      Handle dataset(H5Dopen2(group, column.c_str(), H5P_DEFAULT), H5Dclose, "open " + column);
      check(H5DSattach_scale(dataset, scale, 0), "attach the scale to " + column);
    }
  }
  if (info != nullptr) {
    write_string_attribute(file, "format", "dustlift-series 2");
    write_string_attribute(file, "code_version", info->code_version);
    write_string_attribute(file, "command_line", info->command_line);
    write_string_attribute(file, "scene", info->scene);
    write_fixed_string_attribute(file, "written_at", utc_now());
  }
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
}

void write_string_column_h5(const std::string& path, const std::string& group,
                            const std::string& name, const std::vector<std::string>& values) {
  Handle file(open_or_create(path), H5Fclose, "open or create " + path);
  const std::string group_name = "/" + group;
  if (H5Lexists(file, group_name.c_str(), H5P_DEFAULT) <= 0) {
    Handle created(H5Gcreate2(file, group_name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   H5Gclose, "create group " + group_name);
  }
  Handle g(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + group_name);
  if (H5Lexists(g, name.c_str(), H5P_DEFAULT) > 0)
    check(H5Ldelete(g, name.c_str(), H5P_DEFAULT), "delete " + name);
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size());
  std::string packed(width * values.size(), '\0');
  for (std::size_t k = 0; k < values.size(); ++k)
    packed.replace(k * width, values[k].size(), values[k]);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, width), "string size");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string pad");
  const hsize_t rows = values.size();
  Handle space(H5Screate_simple(1, &rows, nullptr), H5Sclose, "string column space");
  Handle dataset(H5Dcreate2(g, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose, "create dataset " + name);
  if (rows > 0)
    check(H5Dwrite(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()), "write " + name);
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
}

std::vector<std::string> read_string_column_h5(const std::string& path, const std::string& group,
                                               const std::string& name) {
  if (!std::filesystem::exists(path)) throw std::runtime_error("no file " + path);
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + path);
  const std::string dataset_path = "/" + group + "/" + name;
  if (H5Lexists(file, ("/" + group).c_str(), H5P_DEFAULT) <= 0 ||
      H5Lexists(file, dataset_path.c_str(), H5P_DEFAULT) <= 0)
    throw std::runtime_error("no dataset " + dataset_path + " in " + path);
  Handle dataset(H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT), H5Dclose,
                 "open " + dataset_path);
  Handle type(H5Dget_type(dataset), H5Tclose, "type of " + dataset_path);
  Handle space(H5Dget_space(dataset), H5Sclose, "space of " + dataset_path);
  const auto rows = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  const std::size_t width = H5Tget_size(type);
  std::string packed(rows * width, '\0');
  if (rows > 0)
    check(H5Dread(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()),
          "read " + dataset_path);
  std::vector<std::string> values;
  for (std::size_t k = 0; k < rows; ++k) {
    std::string v = packed.substr(k * width, width);
    v.erase(v.find_last_not_of('\0') + 1);
    values.push_back(v);
  }
  return values;
}

}  // namespace dustlift
