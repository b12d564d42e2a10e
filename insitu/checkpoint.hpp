#pragma once
// Checkpoints: a Snapshot (solver/sim/snapshot.hpp) as an HDF5 file OUTDIR/checkpoint.h5.
// VTK- and HDF5-free header (the CLI includes it); layout in docs/reliability.md.
//
// The file is an HDF5 file with a 512-byte user block that holds a text header: magic line,
// total length and an FNV-1a 64-bit hash of every byte after the user block. The reader
// checks the header before HDF5 sees a byte, so a truncated, foreign or corrupted file is
// reported as such (and never reaches the HDF5 parser). h5dump/h5py read the file as usual.
#include <stdexcept>
#include <string>

#include "solver/sim/snapshot.hpp"

namespace dustlift {

/// Any problem reading or writing a checkpoint; the message is one line naming the file and
/// the problem (truncated, not a checkpoint, checksum mismatch, missing array, ...).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Size of the user block that holds the header.
inline constexpr std::size_t kCheckpointHeaderBytes = 512;

/// Writes `snapshot` to `path` atomically: to `path`.tmp, sealed (header + hash), fsync'ed,
/// then renamed over `path` (and the folder fsync'ed). A process killed at any moment
/// leaves either the previous checkpoint or the new one, never a mix.
void write_checkpoint(const std::string& path, const Snapshot& snapshot);

/// Reads and validates a checkpoint. Throws CheckpointError (only) on any problem.
Snapshot read_checkpoint(const std::string& path);

/// Writes the header (length and hash of the bytes after the user block) into the first
/// kCheckpointHeaderBytes of an existing file. write_checkpoint uses it; the fuzz target
/// uses it to feed arbitrary HDF5 payloads past the checksum to the layout reader.
void seal_checkpoint(const std::string& path);

}  // namespace dustlift
