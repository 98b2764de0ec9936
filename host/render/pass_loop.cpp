#include "render/pass_loop.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "render/adaptive_sampling.h"
#include "render/device_pool.h"
#include "render/error_estimate.h"
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

// The next pass, or the stop, decided by the coordinator only: an interrupt (of any rank) first,
// then the schedule (pass_schedule.h: the sample count, the time budget, the target error).
PassDecision decide_next_pass(const Film& film, const ErrorEstimate& film_estimate, const PassTracer& tracer,
                              const GpuRenderParams& params, const PassLoopOptions& options,
                              PassMeasurements& measured, PassScheduleState& schedule) {
  PassDecision d;
  if (interrupted(options) || tracer.others_interrupted()) {
    d.interrupted = true;
    return d;
  }
  measured.max_samples_per_pass = tracer.max_samples_per_pass(params.pixel_count);
  d.next = plan_next_pass(film, film_estimate, options.request, measured, schedule);
  return d;
}

}  // namespace

void DevicePoolTracer::trace(const GpuRenderParams& pass, Film& film, const std::vector<GpuSampleSlot>* slots) {
  pool_.run_pass(pass, film, slots);
}

uint32_t DevicePoolTracer::max_samples_per_pass(uint32_t pixel_count) const {
  return pool_.max_samples_per_pass(pixel_count);
}

std::vector<std::string> DevicePoolTracer::take_notices() { return pool_.take_notices(); }

PassLoopResult run_passes(PassTracer& tracer, const GpuRenderParams& params, Film& film,
                          const PassLoopOptions& options) {
  PassLoopResult result;
  const bool decides = tracer.coordinator();
  Progress progress(options.show_progress && decides);
  const Clock::time_point t0 = Clock::now();
  Clock::time_point last_checkpoint = t0;
  const uint64_t samples_before = film.total_samples();  // a resumed film already holds some
  const uint64_t spp_before = film.samples_per_pixel();
  GpuRenderParams pass = params;
  PassMeasurements measured;
  PassScheduleState schedule;
  AdaptiveSlotTable slot_table;
  std::vector<GpuSampleSlot> slots;  // the adaptive pass's
  // The coordinator's error estimate of the film as it stands, made once after each pass: the
  // progress line shows it and the next decision plans with it.
  ErrorEstimate film_estimate;
  if (decides) film_estimate = estimate_error(film);
  for (;;) {
    print_notices(tracer, progress);
    measured.elapsed_s = seconds_since(t0);
    PassDecision decision;
    if (decides) decision = decide_next_pass(film, film_estimate, tracer, params, options, measured, schedule);
    tracer.share(decision);
    result.estimate = decision.next.estimate;
    if (decision.stop()) {
      result.interrupted = decision.interrupted;
      result.stop = decision.next.stop;
      break;
    }
    pass.sample_begin = decision.next.sample_begin;
    pass.samples_per_pass = decision.next.samples;
    pass.slotted = decision.next.adaptive ? 1u : 0u;
    pass.pixel_count = decision.next.adaptive ? decision.next.slot_count : params.pixel_count;
    // An adaptive pass's slots: the coordinator's round table (adaptive_sampling.h).
    if (decides && decision.next.adaptive) slots = slot_table.pass_slots(film, decision.next, options.request);
    const Clock::time_point pass_start = Clock::now();
    tracer.trace(pass, film, decision.next.adaptive ? &slots : nullptr);
    const double pass_seconds = seconds_since(pass_start);
    result.trace_seconds += pass_seconds;
    const double pass_spp = double(pass.samples_per_pass) * pass.pixel_count / std::max<uint32_t>(params.pixel_count, 1);
    measured.samples_per_pixel_per_s = pass_spp / std::max(1e-9, pass_seconds);
    ++measured.passes;
    ++result.passes;
    if (!decides) continue;
    film_estimate = estimate_error(film);
    ProgressState shown;
    shown.passes = result.passes;
    shown.spp_done = film.samples_per_pixel();
    shown.spp_target = options.request.target_spp;
    shown.samples_per_s = double(film.total_samples() - samples_before) / std::max(1e-9, result.trace_seconds);
    shown.elapsed_s = seconds_since(t0);
    shown.time_limit_s = options.request.time_limit_s;
    shown.spp_this_run = film.samples_per_pixel() - spp_before;
    if (options.request.target_error > 0) {
      shown.target_error = options.request.target_error;
      shown.estimate = film_estimate;
      shown.predicted_spp = predicted_spp_for(shown.estimate, film.samples_per_pixel(), shown.target_error);
    }
    progress.update(shown);
    if (options.checkpoint && seconds_since(last_checkpoint) >= options.checkpoint_every_s) {
      options.checkpoint(film);
      last_checkpoint = Clock::now();
    }
  }
  if (result.interrupted && decides) result.estimate = film_estimate;
  print_notices(tracer, progress);
  progress.finish();
  return result;
}

}  // namespace clpt
