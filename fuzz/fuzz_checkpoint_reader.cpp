// libFuzzer target: read_checkpoint on arbitrary bytes written to a temporary file. Only a
// CheckpointError may escape. The first byte picks the mode:
//  - even: the bytes as they are (exercises the header, length and checksum checks);
//  - odd: the rest placed behind a correct header (sealed by the writer's own code), so the
//    HDF5 parser and the layout checks see arbitrary payloads past the checksum.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "insitu/checkpoint.hpp"

namespace {

std::string temp_path() {
  static const std::string path = "/tmp/dustlift_fuzz_checkpoint_" + std::to_string(::getpid()) + ".h5";
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool sealed = (data[0] & 1) != 0;
  const std::string path = temp_path();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (sealed) out << std::string(dustlift::kCheckpointHeaderBytes, '\0');
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    if (sealed) dustlift::seal_checkpoint(path);
    (void)dustlift::read_checkpoint(path);
  } catch (const dustlift::CheckpointError&) {
    // expected for bad input
  }
  return 0;
}
