// The progress line on stderr: passes, samples per pixel, samples/s and ETA, redrawn in place.
#pragma once

#include <cstdint>

namespace clpt {

class Progress {
 public:
  // enabled: draw at all (the CLI enables it when stderr is a terminal, or on --progress).
  explicit Progress(bool enabled) : enabled_(enabled) {}
  // spp_target 0 means "until the time limit"; time_limit_s 0 means none.
  void update(int passes, uint64_t spp_done, uint64_t spp_target, double samples_per_s,
              double elapsed_s, double time_limit_s);
  void finish();

 private:
  bool enabled_;
  bool drawn_ = false;
};

}  // namespace clpt
