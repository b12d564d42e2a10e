#include "insitu/pvd_collection.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace dustlift {

PvdCollection::PvdCollection(std::string path) : path_(std::move(path)) {}

void PvdCollection::add(double time, const std::string& relative_file) {
  // A repeated time (e.g. on_finish right after an output at the same time) replaces
  // the entry instead of listing two datasets for one timestep.
  if (!entries_.empty() && entries_.back().time == time) {
    entries_.back().file = relative_file;
  } else {
    entries_.push_back({time, relative_file});
  }
  write();
}

void PvdCollection::assign(std::vector<Entry> entries) {
  entries_ = std::move(entries);
  write();
}

void PvdCollection::write() const {
  const std::filesystem::path target(path_);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  const std::filesystem::path temporary = target.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + temporary.string());
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const auto& e : entries_)
      out << fmt::format("    <DataSet timestep=\"{}\" part=\"0\" file=\"{}\"/>\n", e.time, e.file);
    out << "  </Collection>\n</VTKFile>\n";
    out.flush();
    if (!out) throw std::runtime_error("error while writing " + temporary.string());
  }
  std::filesystem::rename(temporary, target);  // atomic on POSIX: never a half-written .pvd
}

std::string numbered_file_name(const std::string& prefix, long long index,
                               const std::string& extension) {
  return fmt::format("{}_{:06d}.{}", prefix, index, extension);
}

}  // namespace dustlift
