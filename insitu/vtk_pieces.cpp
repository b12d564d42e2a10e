#include "insitu/vtk_pieces.hpp"

#include <filesystem>
#include <stdexcept>

#include "solver/core/communicator.hpp"

namespace dustlift {

VtkSeriesFiles piece_series_files(const std::string& output_dir, const std::string& prefix,
                                  const std::string& piece_extension, const RunPiece& piece) {
  return VtkSeriesFiles(output_dir, prefix, "p" + piece_extension, piece.rank == 0);
}

void write_in_pieces(
    VtkSeriesFiles& files, const RunPiece& piece, double time, const std::string& piece_extension,
    const std::function<void(const std::string&)>& write_piece,
    const std::function<void(const std::string&, const std::vector<std::string>&)>& write_summary) {
  if (piece.comm == nullptr) throw std::invalid_argument("write_in_pieces: no communicator");
  const std::string summary = files.next_path(time);
  std::string problem;
  try {
    const std::string path = files.piece_path(piece.rank, piece_extension);
    write_piece(path + ".tmp");
    std::filesystem::rename(path + ".tmp", path);
  } catch (const std::exception& e) {
    problem = e.what();
  }
  // The summary lists only complete pieces: it is written after every rank's rename.
  problem = piece.comm->first_nonempty(problem);
  if (problem.empty()) {
    try {
      if (piece.rank == 0) {
        std::vector<std::string> sources;
        for (int r = 0; r + 1 < static_cast<int>(piece.column_bounds.size()); ++r)
          sources.push_back(files.piece_name(r, piece_extension));
        write_summary(summary, sources);
      }
      files.commit(time);
    } catch (const std::exception& e) {
      problem = e.what();
    }
  }
  problem = piece.comm->first_nonempty(problem);
  if (!problem.empty()) throw std::runtime_error(problem);
}

}  // namespace dustlift
