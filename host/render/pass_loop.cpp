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
void print_notices(PassTracer& tracer, Progress& progress) {
  for (const std::string& notice : tracer.take_notices()) {
    progress.finish();
    std::fprintf(stderr, "clpt: %s\n", notice.c_str());
  }
}

bool interrupted(const PassLoopOptions& options) {
  return options.interrupt && options.interrupt->load(std::memory_order_relaxed);
}

// What the coordinator knows when it decides the next pass.
struct LoopState {
  int passes = 0;
  double elapsed_s = 0;
  double rate = 0;  // samples per pixel per second of the last pass (0: none yet)
};

// The next pass, or the stop: the sample count reached, an interrupt (of any rank), the time
// budget spent. Decided by the coordinator only.
PassDecision decide_next_pass(const Film& film, const PassTracer& tracer, const GpuRenderParams& params,
                              const PassLoopOptions& options, const LoopState& state) {
  PassDecision d;
  const uint64_t stop_spp = options.target_spp ? options.target_spp : kMaxSpp;
  const uint32_t g = options.granularity;
  if (film.samples_per_pixel() >= stop_spp) {
    d.stop = true;
    return d;
  }
  if (interrupted(options) || tracer.others_interrupted()) {
    d.stop = d.interrupted = true;
    return d;
  }
  if (options.time_limit_s > 0 && state.passes > 0 && state.elapsed_s >= options.time_limit_s) {
    d.stop = true;
    return d;
  }
  double pass_s = options.pass_target_s;
  if (options.time_limit_s > 0) pass_s = std::min(pass_s, std::max(0.0, options.time_limit_s - state.elapsed_s));
  d.sample_begin = static_cast<uint32_t>(film.samples_per_pixel());
  d.samples = std::min(next_pass_samples(film.samples_per_pixel(), stop_spp, state.rate, pass_s, g),
                       std::max(g, tracer.max_samples_per_pass(params.pixel_count) / g * g));
  return d;
}

}  // namespace

void DevicePoolTracer::trace(const GpuRenderParams& pass, Film& film) { pool_.run_pass(pass, film); }

uint32_t DevicePoolTracer::max_samples_per_pass(uint32_t pixel_count) const {
  return pool_.max_samples_per_pass(pixel_count);
}

std::vector<std::string> DevicePoolTracer::take_notices() { return pool_.take_notices(); }

uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity) {
  double want = samples_per_pixel_per_s > 0 ? samples_per_pixel_per_s * target_s : granularity;
  want = std::clamp(want, double(granularity), double(kMaxSamplesPerPass));
  uint64_t n = uint64_t(want) / granularity * granularity;
  if (target > 0) n = std::min<uint64_t>(n, target - done);
  return static_cast<uint32_t>(std::max<uint64_t>(n, 1));
}

PassLoopResult run_passes(PassTracer& tracer, const GpuRenderParams& params, Film& film,
                          const PassLoopOptions& options) {
  PassLoopResult result;
  const bool decides = tracer.coordinator();
  Progress progress(options.show_progress && decides);
  const Clock::time_point t0 = Clock::now();
  Clock::time_point last_checkpoint = t0;
  const uint64_t samples_before = film.total_samples();  // a resumed film already holds some
  GpuRenderParams pass = params;
  LoopState state;
  for (;;) {
    print_notices(tracer, progress);
    state.passes = result.passes;
    state.elapsed_s = seconds_since(t0);
    PassDecision next;
    if (decides) next = decide_next_pass(film, tracer, params, options, state);
    tracer.share(next);
    if (next.stop) {
      result.interrupted = next.interrupted;
      break;
    }
    pass.sample_begin = static_cast<clpt_u32>(next.sample_begin);
    pass.samples_per_pass = next.samples;
    const Clock::time_point pass_start = Clock::now();
    tracer.trace(pass, film);
    state.rate = pass.samples_per_pass / std::max(1e-9, seconds_since(pass_start));
    ++result.passes;
    if (!decides) continue;
    progress.update(result.passes, film.samples_per_pixel(), options.target_spp,
                    double(film.total_samples() - samples_before) / std::max(1e-9, seconds_since(t0)),
                    seconds_since(t0), options.time_limit_s);
    if (options.checkpoint && seconds_since(last_checkpoint) >= options.checkpoint_every_s) {
      options.checkpoint(film);
      last_checkpoint = Clock::now();
    }
  }
  print_notices(tracer, progress);
  progress.finish();
  return result;
}

}  // namespace clpt
