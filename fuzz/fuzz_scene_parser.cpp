// libFuzzer target: parse_scene on arbitrary bytes. The parser's contract is that malformed
// input of any kind ends in a SceneError (exit code 2 in the CLI); any other exception, a
// crash or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "solver/scene/scene.hpp"
#include "solver/scene/table_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)dustlift::parse_scene(text, "fuzz.toml");
  } catch (const dustlift::SceneError&) {
    // expected for bad input
  }
  return 0;  // anything else escapes and libFuzzer reports it
}
