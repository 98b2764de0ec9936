// The pixels of one pass, handed out as ranges to the devices of a render (device_pool.h), and
// how large a range one device takes: its own launch sizing (watchdog target, growth and memory
// bounds) and its share of the devices' combined speed. The queue is not thread-safe: the pool
// holds its lock around it.
#pragma once

#include <cstdint>
#include <vector>

namespace clpt {

struct PixelRange {
  uint32_t begin = 0;
  uint32_t count = 0;  // 0: no range
};

class PixelRangeQueue {
 public:
  // The pixels [0, pixels) of a pass, none handed out yet.
  explicit PixelRangeQueue(uint32_t pixels) : next_(0), end_(pixels) {}
  // The pixels of `pixels` only (an MPI rank's part of a pass, render/rank_pass.h).
  explicit PixelRangeQueue(PixelRange pixels) : next_(pixels.begin), end_(pixels.begin + pixels.count) {}

  // Pixels not handed out (ranges given back count again).
  uint32_t remaining() const;
  bool empty() const { return remaining() == 0; }

  // Up to `count` (>= 1) consecutive pixels: from a range given back first, else fresh ones.
  // Returns a range of count 0 when the queue is empty.
  PixelRange take(uint32_t count);

  // A range that was taken but not traced (its device failed): handed out again.
  void give_back(PixelRange range);

 private:
  uint32_t next_, end_;                 // fresh pixels [next_, end_)
  std::vector<PixelRange> given_back_;  // taken first
};

// Pixels of a device's next range. Pure. `launch`: what that device's own launch sizing gives
// (next_launch_pixels: watchdog target, growth bound, memory bound). `share`: the device's
// fraction of the combined throughput of the devices still working (1 alone, or while any
// device is unmeasured). Guided self-scheduling: a device takes at most `share` of what is left
// (but at least `min_pixels`), so ranges shrink towards the end of a pass and the devices finish
// it at about the same time instead of one waiting for another's long last range. The result is
// in [1, remaining] (0 when remaining is 0).
uint32_t balanced_range_pixels(uint32_t launch, uint32_t remaining, double share, uint32_t min_pixels);

// How one device's launches are sized (decided per device in render_plan.cpp).
struct LaunchSizing {
  double target_s = 0.075;           // wall time per launch; <= 0: one launch per pass
  uint32_t first_pixels = 4096;      // pixels of the first launch, before any measurement
  uint32_t max_pixels = UINT32_MAX;  // memory bound: the pass buffer holds 32 B per pixel
  uint32_t max_jobs = UINT32_MAX;    // pixels x samples of a launch (PoCL: one compiled kernel, cl_device.h)
};

// A launch may cover at most this many times the pixels of the one before: small launches
// under-use the device and so under-estimate its throughput; growth by steps stays safe.
constexpr uint32_t kMaxLaunchGrowth = 4;

// Pixels for the next launch of a pass. Pure. remaining: pixels of the pass not yet launched;
// samples: samples per pixel of the pass; pixel_samples_per_s: measured throughput of the last
// launch (0: none yet, use first_pixels); previous: pixels of the last launch (0: none). The
// result is in [1, remaining] (0 when remaining is 0); a tail of under a quarter of a launch is
// folded into it, so passes do not end in a sliver, unless that breaks the memory or job bound.
uint32_t next_launch_pixels(const LaunchSizing& sizing, uint32_t remaining, uint32_t samples,
                            double pixel_samples_per_s, uint32_t previous);

}  // namespace clpt
