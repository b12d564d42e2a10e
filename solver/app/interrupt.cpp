#include "solver/app/interrupt.hpp"

#include <atomic>
#include <csignal>
#include <cstdint>
#include <ctime>

namespace dustlift {
namespace {

// Lock-free atomics, so usable in the handler, which may run on any of the run's threads
// (two signals can be handled on two threads at once).
std::atomic<int> g_signal{0};             // the first signal received, 0 for none
std::atomic<int> g_joined{0};             // later signals within the window of the first
std::atomic<std::int64_t> g_first_ns{0};  // when the first arrived (CLOCK_MONOTONIC, ns)
static_assert(std::atomic<int>::is_always_lock_free &&
              std::atomic<std::int64_t>::is_always_lock_free);
struct sigaction g_previous_int, g_previous_term;

/// Monotonic time in ns (clock_gettime is async-signal-safe).
std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

extern "C" void on_stop_signal(int sig) {
  const std::int64_t now = monotonic_ns();
  int none = 0;
  if (g_signal.load() == 0) {
    g_first_ns.store(now);
    if (g_signal.compare_exchange_strong(none, sig)) return;
  }
  const std::int64_t window = std::chrono::nanoseconds(kStopSignalWindow).count();
  if (now - g_first_ns.load() < window) {
    // The same stop request, delivered twice (to the process and to its group).
    g_joined.fetch_add(1);
    return;
  }
  // A later one: give up the orderly stop (only async-signal-safe calls here).
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  sigaction(sig, &fallback, nullptr);
  raise(sig);
}

}  // namespace

InterruptHandler::InterruptHandler() {
  g_signal.store(0);
  g_joined.store(0);
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // Both signals blocked while the handler runs: a SIGTERM landing inside the SIGINT
  // handler waits until the first one is recorded.
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  action.sa_flags = SA_RESTART;  // writes in progress (VTK, HDF5) carry on
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptHandler::~InterruptHandler() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool InterruptHandler::requested() {
  return g_signal.load() != 0;
}

std::string InterruptHandler::signal_name() {
  const int sig = g_signal.load();
  if (sig == SIGINT) return "SIGINT";
  if (sig == SIGTERM) return "SIGTERM";
  return {};
}

int InterruptHandler::joined_signals() {
  return g_joined.load();
}

}  // namespace dustlift
