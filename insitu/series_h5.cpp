// HDF5 side of SeriesSink (C API). Layout: /<series>/<column> 1-D float64 datasets,
// chunked and extendible, each with a string attribute "units"; the group carries
// "columns" (comma-separated CSV headers, in order) so readers can restore column order.
#include <hdf5.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "insitu/series_table.hpp"

namespace dustlift {
namespace {

/// Closes an HDF5 handle on scope exit.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5: " + what);
  }
  ~Handle() { close_(id_); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: " + what);
}

void write_string_attribute(hid_t object, const char* name, const std::string& value) {
  if (H5Aexists(object, name) > 0) check(H5Adelete(object, name), "delete attribute");
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, value.empty() ? 1 : value.size()), "string size");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string pad");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  check(H5Awrite(attr, type, value.empty() ? "" : value.c_str()), "write attribute");
}

/// Opens the file read-write; creates it when missing or not a readable HDF5 file
/// (e.g. truncated by a killed run: every table is rewritten whole, so nothing is lost
/// that the next writes do not restore).
hid_t open_or_create(const std::string& path) {
  if (std::filesystem::exists(path)) {
    H5E_auto2_t old_func;
    void* old_data;
    H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const hid_t file = H5Fis_hdf5(path.c_str()) > 0
                           ? H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)
                           : H5I_INVALID_HID;
    H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
    if (file >= 0) return file;
  }
  return H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
}

void write_column(hid_t group, const std::string& name, const std::string& unit,
                  const std::vector<double>& values) {
  const hsize_t rows = values.size();
  if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0) {
    const hsize_t initial = 0, unlimited = H5S_UNLIMITED, chunk = 1024;
    Handle space(H5Screate_simple(1, &initial, &unlimited), H5Sclose, "column space");
    Handle props(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset properties");
    check(H5Pset_chunk(props, 1, &chunk), "chunk");
    Handle created(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, props,
                              H5P_DEFAULT),
                   H5Dclose, "create dataset " + name);
    write_string_attribute(created, "units", unit);
  }
  Handle dataset(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
  check(H5Dset_extent(dataset, &rows), "resize dataset " + name);
  if (rows == 0) return;
  Handle file_space(H5Dget_space(dataset), H5Sclose, "dataset space");
  Handle memory_space(H5Screate_simple(1, &rows, nullptr), H5Sclose, "memory space");
  check(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, memory_space, file_space, H5P_DEFAULT,
                 values.data()),
        "write dataset " + name);
}

std::string read_string_attribute(hid_t object, const char* name) {
  Handle attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, std::string("open attribute ") + name);
  Handle type(H5Aget_type(attr), H5Tclose, "attribute type");
  std::string value(H5Tget_size(type), '\0');
  check(H5Aread(attr, type, value.data()), std::string("read attribute ") + name);
  value.erase(value.find_last_not_of('\0') + 1);
  return value;
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
  // Column order comes from "columns" (CSV headers); names and units from the datasets.
  const std::string headers = read_string_attribute(group, "columns");
  std::vector<SeriesColumn> columns;
  std::vector<std::vector<double>> values;
  std::size_t start = 0;
  while (start <= headers.size()) {
    const std::size_t end = std::min(headers.find(',', start), headers.size());
    const std::string header = headers.substr(start, end - start);
    start = end + 1;
    // The dataset whose name + "_" + units equals the header (names may hold '_').
    bool found = false;
    for (std::size_t cut = header.rfind('_'); cut != std::string::npos && cut > 0 && !found;
         cut = header.rfind('_', cut - 1)) {
      const std::string column = header.substr(0, cut), unit = header.substr(cut + 1);
      if (H5Lexists(group, column.c_str(), H5P_DEFAULT) <= 0) continue;
      Handle dataset(H5Dopen2(group, column.c_str(), H5P_DEFAULT), H5Dclose, "open " + column);
      if (read_string_attribute(dataset, "units") != unit) continue;
      Handle space(H5Dget_space(dataset), H5Sclose, "dataset space");
      const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
      std::vector<double> v(n);
      if (n)
        check(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
              "read " + column);
      columns.push_back({column, unit});
      values.push_back(std::move(v));
      found = true;
    }
    if (!found) throw std::runtime_error("series " + name + ": no dataset for column " + header);
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

void write_series_h5(const std::string& path, const SeriesTable& table) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  Handle file(open_or_create(path), H5Fclose, "open or create " + path);
  const std::string group_name = "/" + table.name();
  std::string headers;
  for (std::size_t k = 0; k < table.columns().size(); ++k)
    headers.append(k ? "," : "").append(table.header(k));
  // A group written with other columns (e.g. other stations) is replaced whole.
  if (H5Lexists(file, group_name.c_str(), H5P_DEFAULT) > 0) {
    bool same_columns = false;
    {
      Handle group(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT), H5Gclose, "open group");
      if (H5Aexists(group, "columns") > 0) {
        Handle attr(H5Aopen(group, "columns", H5P_DEFAULT), H5Aclose, "open columns");
        Handle type(H5Aget_type(attr), H5Tclose, "columns type");
        std::string stored(H5Tget_size(type), '\0');
        check(H5Aread(attr, type, stored.data()), "read columns");
        same_columns = stored == headers;
      }
    }
    if (!same_columns) check(H5Ldelete(file, group_name.c_str(), H5P_DEFAULT), "delete group");
  }
  if (H5Lexists(file, group_name.c_str(), H5P_DEFAULT) <= 0) {
    Handle created(H5Gcreate2(file, group_name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   H5Gclose, "create group " + group_name);
    write_string_attribute(created, "columns", headers);
  }
  Handle group(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT), H5Gclose, "open group");
  for (std::size_t k = 0; k < table.columns().size(); ++k)
    write_column(group, table.columns()[k].name, table.columns()[k].unit, table.column(k));
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
}

void write_string_column_h5(const std::string& path, const std::string& group, const std::string& name,
                            const std::vector<std::string>& values) {
  Handle file(open_or_create(path), H5Fclose, "open or create " + path);
  const std::string group_name = "/" + group;
  if (H5Lexists(file, group_name.c_str(), H5P_DEFAULT) <= 0) {
    Handle created(H5Gcreate2(file, group_name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                   "create group " + group_name);
  }
  Handle g(H5Gopen2(file, group_name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + group_name);
  if (H5Lexists(g, name.c_str(), H5P_DEFAULT) > 0) check(H5Ldelete(g, name.c_str(), H5P_DEFAULT), "delete " + name);
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size());
  std::string packed(width * values.size(), '\0');
  for (std::size_t k = 0; k < values.size(); ++k) packed.replace(k * width, values[k].size(), values[k]);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, width), "string size");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string pad");
  const hsize_t rows = values.size();
  Handle space(H5Screate_simple(1, &rows, nullptr), H5Sclose, "string column space");
  Handle dataset(H5Dcreate2(g, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
                 "create dataset " + name);
  if (rows > 0) check(H5Dwrite(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()), "write " + name);
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
}

std::vector<std::string> read_string_column_h5(const std::string& path, const std::string& group,
                                               const std::string& name) {
  if (!std::filesystem::exists(path)) throw std::runtime_error("no file " + path);
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open " + path);
  const std::string dataset_path = "/" + group + "/" + name;
  if (H5Lexists(file, ("/" + group).c_str(), H5P_DEFAULT) <= 0 || H5Lexists(file, dataset_path.c_str(), H5P_DEFAULT) <= 0)
    throw std::runtime_error("no dataset " + dataset_path + " in " + path);
  Handle dataset(H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT), H5Dclose, "open " + dataset_path);
  Handle type(H5Dget_type(dataset), H5Tclose, "type of " + dataset_path);
  Handle space(H5Dget_space(dataset), H5Sclose, "space of " + dataset_path);
  const auto rows = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  const std::size_t width = H5Tget_size(type);
  std::string packed(rows * width, '\0');
  if (rows > 0) check(H5Dread(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()), "read " + dataset_path);
  std::vector<std::string> values;
  for (std::size_t k = 0; k < rows; ++k) {
    std::string v = packed.substr(k * width, width);
    v.erase(v.find_last_not_of('\0') + 1);
    values.push_back(v);
  }
  return values;
}

}  // namespace dustlift
