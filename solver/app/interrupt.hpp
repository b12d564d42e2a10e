#pragma once
// SIGINT (Ctrl-C) and SIGTERM during a run's time loop: the first one asks the run to stop
// after the step it is in (its outputs finished, a checkpoint written, every collection
// consistent; exit code kExitInterrupted); a second one ends the process at once (the
// signal's default action), for a user who does not want to wait for the checkpoint.
#include <string>

namespace dustlift {

class InterruptHandler {
 public:
  /// Installs the handlers (and clears an earlier request); the destructor puts the
  /// previous ones back.
  InterruptHandler();
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

  /// Whether a SIGINT or SIGTERM arrived since the handler was installed.
  static bool requested();
  /// "SIGINT" or "SIGTERM" (empty when none arrived).
  static std::string signal_name();
};

}  // namespace dustlift
