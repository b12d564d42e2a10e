#pragma once
// SIGINT (Ctrl-C) and SIGTERM during a run's time loop: the first one asks the run to stop
// after the step it is in (its outputs finished, a checkpoint written, every collection
// consistent; exit code kExitInterrupted). Signals within kStopSignalWindow of the first
// belong to the same stop request: `timeout`, `mpirun` and batch systems deliver one signal
// to the process and another to its process group, a few milliseconds apart. A signal after
// that window ends the process at once (the signal's default action), for a user who does
// not want to wait for the checkpoint.
#include <chrono>
#include <string>

namespace dustlift {

/// Signals that arrive this soon after the first one count as the same stop request.
inline constexpr std::chrono::milliseconds kStopSignalWindow{1000};

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
  /// Signals that joined the first one's stop request (arrived within kStopSignalWindow).
  static int joined_signals();
};

}  // namespace dustlift
