// Checkpoint files (HDF5 C API). Layout: groups run/, gas/, parcels/, dem/, coupling/,
// scene/ holding 1-D datasets named as in the Snapshot (float64, int64, int32, int8;
// texts as fixed-length strings); root attribute "format" = "dustlift-checkpoint 1".
// A 512-byte user block carries the header checked before HDF5 opens the file.
#include "insitu/checkpoint.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "insitu/hdf5_handle.hpp"

namespace dustlift {
namespace {

constexpr const char* kMagic = "DUSTLIFT-CHECKPOINT 1\n";
constexpr const char* kFormat = "dustlift-checkpoint 1";
const char* const kGroups[] = {"run", "gas", "parcels", "dem", "coupling", "scene", "insitu"};
/// Groups a checkpoint may lack: the parcel groups of a gas-only run, the in-situ group of a
/// run without outputs that carry state.
bool optional_group(const std::string& g) {
  return g == "parcels" || g == "dem" || g == "coupling" || g == "insitu";
}
/// Nesting below a top-level group (insitu/<observer>/<series>/<column>) and entries in all:
/// bounds for a forged file.
constexpr int kMaxGroupDepth = 4;
constexpr hsize_t kMaxEntries = 100000;

/// FNV-1a, 64 bit: simple, no table, catches truncation and bit flips (not an attacker).
std::uint64_t fnv1a64(const char* data, std::size_t n) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (std::size_t k = 0; k < n; ++k) {
    h ^= static_cast<unsigned char>(data[k]);
    h *= 0x100000001b3ULL;
  }
  return h;
}

using Handle = Hdf5Handle<CheckpointError>;
constexpr auto check = hdf5_check<CheckpointError>;

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw CheckpointError(path + ": is a folder, not a checkpoint file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError(path + ": cannot open checkpoint file");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw CheckpointError(path + ": cannot read checkpoint file");
  return s.str();
}

// ------------------------------------------------------------------ writing
template <class T>
void write_dataset(hid_t file, const std::string& name, hid_t file_type, hid_t memory_type,
                   const std::vector<T>& values) {
  const hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "dataspace for " + name);
  Handle links(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "link properties");
  check(H5Pset_create_intermediate_group(links, 1), "intermediate groups");
  Handle set(H5Dcreate2(file, name.c_str(), file_type, space, links, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose, "create dataset " + name);
  if (n > 0)
    check(H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "write " + name);
}

void write_text(hid_t file, const std::string& name, const std::string& text) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, text.empty() ? 1 : text.size()), "string size");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "string padding");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle links(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "link properties");
  check(H5Pset_create_intermediate_group(links, 1), "intermediate groups");
  Handle set(H5Dcreate2(file, name.c_str(), type, space, links, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
             "create dataset " + name);
  const std::string padded = text.empty() ? std::string(1, '\0') : text;
  check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, padded.data()), "write " + name);
}

void write_format_attribute(hid_t file) {
  const std::string value = kFormat;
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(type, value.size()), "string size");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(file, "format", type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create format");
  check(H5Awrite(attr, type, value.data()), "write format");
}

void fsync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw CheckpointError(path + ": cannot open for fsync");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw CheckpointError(path + ": fsync failed");
}

// ------------------------------------------------------------------ reading
/// Element type class of a dataset we know how to read.
enum class Kind { F64, I64, I32, I8, Text };

Kind kind_of(hid_t type, const std::string& name) {
  const H5T_class_t c = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  if (c == H5T_FLOAT && size == 8) return Kind::F64;
  if (c == H5T_INTEGER && size == 8) return Kind::I64;
  if (c == H5T_INTEGER && size == 4) return Kind::I32;
  if (c == H5T_INTEGER && size == 1) return Kind::I8;
  if (c == H5T_STRING && H5Tis_variable_str(type) == 0) return Kind::Text;
  throw CheckpointError("dataset '" + name + "' has an element type a checkpoint never uses");
}

template <class T>
std::vector<T> read_numbers(hid_t set, hid_t memory_type, hsize_t n, const std::string& name) {
  std::vector<T> v(static_cast<std::size_t>(n));
  if (n > 0)
    check(H5Dread(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          "cannot read " + name);
  return v;
}

void read_dataset(hid_t file, const std::string& name, std::size_t file_bytes, Snapshot& s) {
  H5O_type_t object_type = H5O_TYPE_UNKNOWN;
  if (H5Oexists_by_name(file, name.c_str(), H5P_DEFAULT) <= 0)
    throw CheckpointError("'" + name + "' is not an object");
  Handle object(H5Oopen(file, name.c_str(), H5P_DEFAULT), H5Oclose, "cannot open '" + name + "'");
  object_type = H5Iget_type(object) == H5I_DATASET ? H5O_TYPE_DATASET : H5O_TYPE_UNKNOWN;
  if (object_type != H5O_TYPE_DATASET) throw CheckpointError("'" + name + "' is not a dataset");
  Handle type(H5Dget_type(object), H5Tclose, "type of " + name);
  Handle space(H5Dget_space(object), H5Sclose, "dataspace of " + name);
  const Kind kind = kind_of(type, name);
  const int rank = H5Sget_simple_extent_ndims(space);
  if (kind == Kind::Text ? rank != 0 : rank != 1)
    throw CheckpointError("dataset '" + name + "' has the wrong rank");
  const hssize_t points = H5Sget_simple_extent_npoints(space);
  const std::size_t element = H5Tget_size(type);
  // Nothing we write is compressed: more data than the file holds means a forged extent.
  if (points < 0 || element == 0 || static_cast<std::size_t>(points) > file_bytes / element) {
    throw CheckpointError("dataset '" + name + "' claims more data than the file holds");
  }
  const auto n = static_cast<hsize_t>(points);
  switch (kind) {
    case Kind::F64:
      s.f64[name] = read_numbers<double>(object, H5T_NATIVE_DOUBLE, n, name);
      break;
    case Kind::I64:
      s.i64[name] = read_numbers<std::int64_t>(object, H5T_NATIVE_INT64, n, name);
      break;
    case Kind::I32:
      s.i32[name] = read_numbers<std::int32_t>(object, H5T_NATIVE_INT32, n, name);
      break;
    case Kind::I8:
      s.i8[name] = read_numbers<std::int8_t>(object, H5T_NATIVE_INT8, n, name);
      break;
    case Kind::Text: {
      std::string text(element, '\0');
      check(H5Dread(object, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()),
            "cannot read " + name);
      text.erase(text.find_last_not_of('\0') + 1);
      s.text[name] = text;
      break;
    }
  }
}

std::string read_format(hid_t file) {
  if (H5Aexists(file, "format") <= 0) return {};
  Handle attr(H5Aopen(file, "format", H5P_DEFAULT), H5Aclose, "cannot open attribute format");
  Handle type(H5Aget_type(attr), H5Tclose, "type of attribute format");
  if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) != 0) return {};
  const std::size_t size = H5Tget_size(type);
  if (size == 0 || size > 256) return {};
  Handle space(H5Aget_space(attr), H5Sclose, "space of attribute format");
  if (H5Sget_simple_extent_npoints(space) != 1) return {};
  std::string value(size, '\0');
  check(H5Aread(attr, type, value.data()), "cannot read attribute format");
  value.erase(value.find_last_not_of('\0') + 1);
  return value;
}

/// Reads every dataset of group `path` into `s`, and its sub-groups down to kMaxGroupDepth.
void read_group(hid_t file, const std::string& path, int depth, std::size_t file_bytes,
                hsize_t& entries, Snapshot& s) {
  Handle group(H5Gopen2(file, path.c_str(), H5P_DEFAULT), H5Gclose,
               "'" + path + "' is not a group");
  H5G_info_t info;
  check(H5Gget_info(group, &info), "cannot list group '" + path + "'");
  entries += info.nlinks;
  if (info.nlinks > 1000 || entries > kMaxEntries)
    throw CheckpointError("group '" + path + "' has too many entries");
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t len =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (len <= 0 || len > 256) throw CheckpointError("bad entry name in group '" + path + "'");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    const std::string full = path + "/" + name;
    if (H5Oexists_by_name(file, full.c_str(), H5P_DEFAULT) <= 0)
      throw CheckpointError("'" + full + "' is not an object");
    bool is_group = false;
    {
      Handle object(H5Oopen(file, full.c_str(), H5P_DEFAULT), H5Oclose,
                    "cannot open '" + full + "'");
      is_group = H5Iget_type(object) == H5I_GROUP;
    }
    if (is_group) {
      if (depth >= kMaxGroupDepth) throw CheckpointError("group '" + full + "' is nested too deep");
      read_group(file, full, depth + 1, file_bytes, entries, s);
    } else {
      read_dataset(file, full, file_bytes, s);
    }
  }
}

Snapshot read_layout(const std::string& path, std::size_t file_bytes) {
  QuietHdf5 quiet;
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw CheckpointError("not an HDF5 file behind the checkpoint header");
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
              "HDF5 cannot open the file");
  if (read_format(file) != kFormat)
    throw CheckpointError("HDF5 file without the dustlift checkpoint layout (no format attribute)");
  Snapshot s;
  hsize_t entries = 0;
  for (const char* g : kGroups) {
    if (H5Lexists(file, g, H5P_DEFAULT) <= 0) {
      if (optional_group(g)) continue;
      throw CheckpointError(std::string("no group '") + g + "'");
    }
    // Only the in-situ group nests (observer / series / column).
    read_group(file, g, std::string(g) == "insitu" ? 1 : kMaxGroupDepth, file_bytes, entries, s);
  }
  return s;
}

}  // namespace

void seal_checkpoint(const std::string& path) {
  std::string bytes;
  try {
    bytes = read_file(path);
  } catch (const CheckpointError& e) {
    throw CheckpointError(std::string("sealing ") + e.what());
  }
  if (bytes.size() < kCheckpointHeaderBytes) throw CheckpointError(path + ": too short to seal");
  const std::uint64_t hash =
      fnv1a64(bytes.data() + kCheckpointHeaderBytes, bytes.size() - kCheckpointHeaderBytes);
  char header[kCheckpointHeaderBytes] = {};
  std::snprintf(header, sizeof header, "%slength %llu\nfnv1a64 %016llx\n", kMagic,
                static_cast<unsigned long long>(bytes.size()),
                static_cast<unsigned long long>(hash));
  const int fd = ::open(path.c_str(), O_WRONLY);
  if (fd < 0) throw CheckpointError(path + ": cannot open to seal");
  const ssize_t written = ::pwrite(fd, header, sizeof header, 0);
  const int synced = ::fsync(fd);
  ::close(fd);
  if (written != static_cast<ssize_t>(sizeof header) || synced != 0)
    throw CheckpointError(path + ": cannot write the header");
}

void write_checkpoint(const std::string& path, const Snapshot& s) {
  const std::string tmp = path + ".tmp";
  try {
    QuietHdf5 quiet;
    std::filesystem::remove(tmp);
    {
      Handle create(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file properties");
      check(H5Pset_userblock(create, kCheckpointHeaderBytes), "user block");
      Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, create, H5P_DEFAULT), H5Fclose,
                  "cannot create " + tmp);
      write_format_attribute(file);
      for (const auto& [name, v] : s.f64)
        write_dataset(file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v);
      for (const auto& [name, v] : s.i64)
        write_dataset(file, name, H5T_STD_I64LE, H5T_NATIVE_INT64, v);
      for (const auto& [name, v] : s.i32)
        write_dataset(file, name, H5T_STD_I32LE, H5T_NATIVE_INT32, v);
      for (const auto& [name, v] : s.i8)
        write_dataset(file, name, H5T_STD_I8LE, H5T_NATIVE_INT8, v);
      for (const auto& [name, t] : s.text) write_text(file, name, t);
      check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + tmp);
    }
    seal_checkpoint(tmp);  // also fsyncs the data
    std::filesystem::rename(tmp, path);
    const std::string dir = std::filesystem::path(path).parent_path().string();
    fsync_path(dir.empty() ? "." : dir, O_RDONLY | O_DIRECTORY);
  } catch (const CheckpointError& e) {
    throw CheckpointError(path + ": writing the checkpoint failed: " + e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    throw CheckpointError(path + ": writing the checkpoint failed: " + e.what());
  }
}

Snapshot read_checkpoint(const std::string& path) {
  const std::string bytes = read_file(path);
  const std::size_t magic_len = std::strlen(kMagic);
  if (bytes.compare(0, magic_len, kMagic) != 0) {
    const bool hdf5 = bytes.compare(0, 8, "\x89HDF\r\n\x1a\n") == 0;
    throw CheckpointError(
        path + (hdf5 ? ": an HDF5 file but not a dustlift checkpoint (no checkpoint header)"
                     : ": not a dustlift checkpoint (foreign file: no checkpoint header)"));
  }
  unsigned long long length = 0, hash = 0;
  const std::string header = bytes.substr(0, std::min(bytes.size(), kCheckpointHeaderBytes));
  if (std::sscanf(header.c_str() + magic_len, "length %llu\nfnv1a64 %16llx", &length, &hash) != 2) {
    throw CheckpointError(path + ": corrupt checkpoint header");
  }
  if (bytes.size() < length) {
    throw CheckpointError(path + ": truncated checkpoint (" + std::to_string(bytes.size()) +
                          " of " + std::to_string(length) + " bytes)");
  }
  if (bytes.size() != length || length < kCheckpointHeaderBytes) {
    throw CheckpointError(path + ": corrupt checkpoint (length " + std::to_string(bytes.size()) +
                          " bytes, header says " + std::to_string(length) + ")");
  }
  if (fnv1a64(bytes.data() + kCheckpointHeaderBytes, bytes.size() - kCheckpointHeaderBytes) !=
      hash) {
    throw CheckpointError(path + ": corrupt checkpoint (checksum mismatch)");
  }
  try {
    return read_layout(path, bytes.size());
  } catch (const CheckpointError& e) {
    throw CheckpointError(path + ": " + e.what());
  }
}

}  // namespace dustlift
