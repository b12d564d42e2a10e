#pragma once
// How OpenMP threads wait between parallel regions, chosen once for the dustlift programs.
//
// A coupled step has about 130 fork/join and barrier points (the DEM sub-steps, the gas
// stages, the coupling passes). With OMP_WAIT_POLICY=passive every one of them puts the
// waiting thread to sleep in the kernel; on this project's virtual 2-core machine waking it
// again took up to ~0.2 ms, and the paper scene ran 1.1-1.4x slower (the more the busier the
// host) than with threads that spin a little first (docs/performance.md, "Waiting threads"). Spinning without bound is no
// answer either: when another job shares the cores, a spinning thread burns the time slice
// its partner needs. The default is therefore passive waiting after a short spin
// (GOMP_SPINCOUNT = kDefaultSpinCount, tens of microseconds): the gaps inside a step are
// bridged, a thread idle for longer sleeps.
//
// libgomp reads both variables when it is loaded, before main, so a program that sets them
// must start itself again (reexec_with_default_wait_policy).
#include <string>

namespace dustlift {

/// Spin iterations before a waiting thread sleeps (libgomp's GOMP_SPINCOUNT).
inline constexpr const char* kDefaultSpinCount = "10000";

/// Sets OMP_WAIT_POLICY=passive and GOMP_SPINCOUNT=kDefaultSpinCount when the user set
/// neither (a user's choice of either is kept as it is). Returns whether it changed the
/// environment.
bool set_default_wait_policy();

/// set_default_wait_policy(), then, if it changed anything, replaces the process by the same
/// program with the same arguments (/proc/self/exe). Returns only if nothing changed or the
/// restart failed (the run then waits as the runtime's default says).
void reexec_with_default_wait_policy(char** argv);

/// One line for run logs and benchmark output: how threads wait in this process.
std::string wait_policy_description();

}  // namespace dustlift
