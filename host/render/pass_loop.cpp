#include "render/pass_loop.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "render/device_pool.h"
#include "render/limits.h"
#include "render/progress.h"
#include "util/clock.h"

namespace clpt {
namespace {

// Tells the user about devices that failed (their work went to the others), below the progress line.
void print_notices(DevicePool& pool, Progress& progress) {
  for (const std::string& notice : pool.take_notices()) {
    progress.finish();
    std::fprintf(stderr, "clpt: %s\n", notice.c_str());
  }
}

bool interrupted(const PassLoopOptions& options) {
  return options.interrupt && options.interrupt->load(std::memory_order_relaxed);
}

}  // namespace

uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity) {
  double want = samples_per_pixel_per_s > 0 ? samples_per_pixel_per_s * target_s : granularity;
  want = std::clamp(want, double(granularity), double(kMaxSamplesPerPass));
  uint64_t n = uint64_t(want) / granularity * granularity;
  if (target > 0) n = std::min<uint64_t>(n, target - done);
  return static_cast<uint32_t>(std::max<uint64_t>(n, 1));
}

PassLoopResult run_passes(DevicePool& pool, const GpuRenderParams& params, Film& film,
                          const PassLoopOptions& options) {
  PassLoopResult result;
  const uint64_t stop_spp = options.target_spp ? options.target_spp : kMaxSpp;
  const uint32_t g = options.granularity;
  Progress progress(options.show_progress);
  const Clock::time_point t0 = Clock::now();
  Clock::time_point last_checkpoint = t0;
  const uint64_t samples_before = film.total_samples();  // a resumed film already holds some
  GpuRenderParams pass = params;
  double rate = 0;  // samples per pixel per second
  while (film.samples_per_pixel() < stop_spp) {
    print_notices(pool, progress);
    if (interrupted(options)) {
      result.interrupted = true;
      break;
    }
    const double elapsed = seconds_since(t0);
    if (options.time_limit_s > 0 && result.passes > 0 && elapsed >= options.time_limit_s) break;
    double pass_s = options.pass_target_s;
    if (options.time_limit_s > 0) pass_s = std::min(pass_s, std::max(0.0, options.time_limit_s - elapsed));
    pass.sample_begin = static_cast<clpt_u32>(film.samples_per_pixel());
    pass.samples_per_pass = std::min(
        next_pass_samples(film.samples_per_pixel(), stop_spp, rate, pass_s, g),
        std::max(g, pool.max_samples_per_pass(params.pixel_count) / g * g));
    const Clock::time_point pass_start = Clock::now();
    pool.run_pass(pass, film);
    rate = pass.samples_per_pass / std::max(1e-9, seconds_since(pass_start));
    ++result.passes;
    progress.update(result.passes, film.samples_per_pixel(), options.target_spp,
                    double(film.total_samples() - samples_before) / std::max(1e-9, seconds_since(t0)),
                    seconds_since(t0), options.time_limit_s);
    if (options.checkpoint && seconds_since(last_checkpoint) >= options.checkpoint_every_s) {
      options.checkpoint(film);
      last_checkpoint = Clock::now();
    }
  }
  print_notices(pool, progress);
  progress.finish();
  return result;
}

}  // namespace clpt
