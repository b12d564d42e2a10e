#pragma once
// What the parser knows of one scene key it declared or read: the facts the scene-key
// reference is made of (solver/scene/scene_keys.hpp). Recorded as the parser reads, so the
// reference shows the parser's own defaults and ranges.
#include <string>

namespace dustlift {

struct KeyFact {
  std::string kind;      ///< "number", "integer", "boolean", "string", "one of", "file", ...
  std::string fallback;  ///< the default as TOML text, "required", "optional" or "from <keys>"
  std::string range;     ///< the allowed values ("" when any)
};

}  // namespace dustlift
