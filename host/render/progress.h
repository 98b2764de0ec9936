// The progress line on stderr: passes, samples per pixel, samples/s and ETA, redrawn in place;
// with a target error, the current error estimate and the ETA to the target.
#pragma once

#include <cstdint>

#include "render/error_estimate.h"

namespace clpt {

// What one redraw shows.
struct ProgressState {
  int passes = 0;
  uint64_t spp_done = 0;
  uint64_t spp_target = 0;     // 0: no sample limit
  uint64_t spp_this_run = 0;   // samples per pixel this process added (a resumed film had some)
  double samples_per_s = 0;    // this run's samples over the passes' time (PassLoopResult::trace_seconds)
  double elapsed_s = 0;
  double time_limit_s = 0;     // 0: none
  double target_error = 0;     // 0: none; else estimate and predicted_spp are shown
  ErrorEstimate estimate;
  uint64_t predicted_spp = 0;  // samples per pixel the target needs, by the estimate; 0 unknown
};

class Progress {
 public:
  // enabled: draw at all (the CLI enables it when stderr is a terminal, or on --progress).
  explicit Progress(bool enabled) : enabled_(enabled) {}
  void update(const ProgressState& state);
  void finish();

 private:
  bool enabled_;
  bool drawn_ = false;
};

// Seconds left, the least of: the sample target, the time limit and (with a target error) the
// predicted samples, each at the rate so far. Negative: unknown.
double progress_eta_s(const ProgressState& state);

}  // namespace clpt
