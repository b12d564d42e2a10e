#pragma once
// ParaView .pvd collection written by hand (VTK has no PVD writer outside ParaView):
// <VTKFile type="Collection"><Collection><DataSet timestep=".." part="0" file=".."/>...
// The whole file is rewritten (to a temporary, then renamed) after each added step,
// so a run killed at any moment leaves a valid collection of the files written so far.
#include <string>
#include <vector>

namespace dustlift {

class PvdCollection {
 public:
  /// `path` of the .pvd; dataset file names are stored relative to its folder.
  explicit PvdCollection(std::string path);

  /// Records (time in s, file name relative to the .pvd folder) and rewrites the file.
  void add(double time, const std::string& relative_file);

  struct Entry {
    double time;
    std::string file;
  };
  const std::vector<Entry>& entries() const { return entries_; }
  /// Replaces every entry (a continued run: the entries of its checkpoint) and rewrites the file.
  void assign(std::vector<Entry> entries);
  const std::string& path() const { return path_; }

 private:
  void write() const;
  std::string path_;
  std::vector<Entry> entries_;
};

/// "gas_000042.vtr"-style names: prefix, 6-digit zero-padded index, extension.
std::string numbered_file_name(const std::string& prefix, long long index,
                               const std::string& extension);

}  // namespace dustlift
