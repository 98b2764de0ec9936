// Wall-clock intervals for reports and launch sizing: the steady clock, in seconds; and the
// process's CPU time, for figures that must not depend on what else the machine runs.
#pragma once

#include <chrono>
#include <ctime>

namespace clpt {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU seconds used so far by every thread of this process (an OpenCL CPU driver's worker threads
// included). Over a pass on a CPU device this is the pass's work, whatever else shares the cores;
// on a GPU it is only the host's part.
inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace clpt
