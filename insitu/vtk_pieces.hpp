#pragma once
// One output of a VTK series written in pieces by the ranks of a decomposed run: each rank
// its slab's piece, rank 0 the summary file (.pvtr/.pvtp) that the .pvd lists
// (docs/output.md). VTK-free.
#include <functional>
#include <string>
#include <vector>

#include "insitu/vtk_writers.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

/// A series' numbering for a decomposed run: the summary files' (extension "p" +
/// `piece_extension`), listed in the .pvd by rank 0 only.
VtkSeriesFiles piece_series_files(const std::string& output_dir, const std::string& prefix,
                                  const std::string& piece_extension, const RunPiece& piece);

/// Collective: writes this rank's piece of the dataset of `time` with `write_piece(path)`,
/// then, once every rank's piece is complete, rank 0 writes the summary with
/// `write_summary(path, sources)` (sources: every rank's piece file, relative to the
/// summary) and lists it. Every file is written under a temporary name and renamed when
/// complete. A failure on any rank throws std::runtime_error on every rank with the message
/// of the lowest such rank.
void write_in_pieces(
    VtkSeriesFiles& files, const RunPiece& piece, double time, const std::string& piece_extension,
    const std::function<void(const std::string&)>& write_piece,
    const std::function<void(const std::string&, const std::vector<std::string>&)>& write_summary);

}  // namespace dustlift
