#pragma once
// A private X server for in-situ renders when the run has no display: Debian's ParaView and
// VTK are built for GLX only (no OSMesa, no EGL), so a render window needs an X server even
// offscreen. Xvfb renders through Mesa's llvmpipe, the same software rasterizer OSMesa uses.
#include <sys/types.h>

#include <string>

namespace dustlift {

class VirtualDisplay {
 public:
  /// Starts Xvfb (-displayfd: it picks a free display itself) and sets DISPLAY for this
  /// process; throws std::runtime_error with the reason when Xvfb cannot start.
  VirtualDisplay();
  ~VirtualDisplay();
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;
  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

}  // namespace dustlift
