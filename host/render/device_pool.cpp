#include "render/device_pool.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <stdexcept>
#include <thread>
#include <utility>

#include "cl/cl_context.h"
#include "cl/cl_error.h"
#include "kernels/aov_channels.h"
#include "render/limits.h"
#include "render/megakernel_renderer.h"
#include "render/wavefront_renderer.h"
#include "util/clock.h"

namespace clpt {
namespace {

// The renderer of an execution form, with its program built as the device's plan says.
std::unique_ptr<Renderer> make_renderer(const DevicePlan& plan, DeviceContext& ctx, const DeviceScene& scene) {
  if (plan.form == ExecutionForm::Wavefront)
    return std::make_unique<WavefrontRenderer>(ctx, scene, plan.features, plan.paths_in_flight, plan.local_size);
  return std::make_unique<MegakernelRenderer>(ctx, scene, plan.features, plan.local_size);
}

// Pixel-samples traced and the wall time they took.
struct Throughput {
  double pixel_samples = 0;
  double seconds = 0;
  double rate() const { return seconds > 0 ? pixel_samples / seconds : 0; }
};

// CLPT_INJECT_FAULT=perturb:D:C:F: every sample of the range as if F times brighter in channel C,
// so the sum of a pixel's samples scales by F and the sum of their squares by F^2. Applied here,
// where both execution forms' results enter the film, and nowhere else.
void apply_perturbation(const std::array<double, 3>& factors, std::vector<GpuPixelPass>& result) {
  if (factors[0] == 1 && factors[1] == 1 && factors[2] == 1) return;
  for (GpuPixelPass& px : result)
    for (int c = 0; c < 3; ++c) {
      px.sum[c] = float(double(px.sum[c]) * factors[size_t(c)]);
      px.sum_sq[c] = float(double(px.sum_sq[c]) * factors[size_t(c)] * factors[size_t(c)]);
    }
}

}  // namespace

struct DevicePool::Member {
  size_t position = 0;  // in the --device list; CLPT_INJECT_FAULT's device number
  DeviceInfo info;
  std::unique_ptr<DeviceContext> ctx;
  std::unique_ptr<Renderer> renderer;
  LaunchSizing sizing;
  double launch_rate = 0;        // pixel-samples/s of its last range (sizes the next one)
  uint32_t previous_pixels = 0;  // pixels of its last range
  // Its share of the work follows its throughput over the last pass and this one: recent enough
  // to follow a change of load, long enough to forget a slow first launch (a new launch size).
  Throughput last_pass, this_pass;
  std::vector<StageTime> warm_up_stages;  // the renderer's stage times of warm_up, not of a pass
  uint64_t launches_started = 0;
  bool failed = false;
  std::exception_ptr error;
  DeviceShare share;
};

struct DevicePool::PassState {
  explicit PassState(PixelRange pixels) : queue(pixels) {}
  PixelRangeQueue queue;
  int in_flight = 0;  // ranges taken and not yet added or given back
};

DevicePool::DevicePool(const RenderPlan& plan, const DeviceScene& scene, FaultPlan faults)
    : faults_(std::move(faults)) {
  for (const DevicePlan& d : plan.devices) {
    // A kernel whose triangle loop tests the meshes of large triangles starts its traversal at
    // node 1: the scene must have been converted with them apart (RenderPlan::loop_meshes_apart).
    if (d.features.loop_beside_hierarchy() && scene.loop_triangles != uint32_t(d.features.loop_triangles))
      throw std::logic_error("DevicePool: the device scene's loop triangles (" + std::to_string(scene.loop_triangles) +
                             ") are not the kernel's (" + std::to_string(d.features.loop_triangles) + ")");
    members_.push_back(std::make_unique<Member>());
    members_.back()->position = d.position;
    members_.back()->info = d.device;
    members_.back()->sizing = d.sizing;
    members_.back()->share.device = d.device.label();
    members_.back()->share.form = d.form;
  }
  std::vector<std::thread> threads;
  for (size_t i = 1; i < members_.size(); ++i)
    threads.emplace_back([&, i] { build(*members_[i], plan.devices[i], scene); });
  build(*members_[0], plan.devices[0], scene);
  for (std::thread& t : threads) t.join();
  if (fatal_) std::rethrow_exception(fatal_);
  if (working_count() == 0) throw_every_device_failed();
  // Told now, when it is known that other devices carry on.
  for (const auto& m : members_)
    if (m->failed)
      notices_.push_back("device " + std::to_string(m->position) + " (" + m->share.device + ") failed: " +
                         m->share.failure + "; its work goes to the other devices");
}

DevicePool::~DevicePool() = default;

void DevicePool::build(Member& m, const DevicePlan& plan, const DeviceScene& scene) {
  try {
    if (faults_.fails_build(m.position))
      FaultPlan::throw_injected(CL_BUILD_PROGRAM_FAILURE, "clBuildProgram", m.info.label());
    check_precision_supported(plan.features.precision, m.info);
    m.ctx = std::make_unique<DeviceContext>(m.info);
    if (plan.kernel_cache) m.ctx->use_default_kernel_cache();
    m.share.device = m.ctx->where();
    check_device_memory(plan.memory, m.info);
    m.renderer = make_renderer(plan, *m.ctx, scene);
    m.share.build_seconds = m.renderer->build_seconds();
    m.share.built = true;
  } catch (const Error& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    m.failed = true;
    m.share.failure = e.what();
    m.error = std::current_exception();
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!fatal_) fatal_ = std::current_exception();
  }
}

double DevicePool::warm_up(const GpuRenderParams& params) {
  const Clock::time_point start = Clock::now();
  std::vector<Member*> working;
  for (const auto& m : members_)
    if (!m->failed) working.push_back(m.get());
  std::vector<std::thread> threads;
  for (size_t i = 1; i < working.size(); ++i) threads.emplace_back([&, i] { warm_up(*working[i], params); });
  if (!working.empty()) warm_up(*working[0], params);
  for (std::thread& t : threads) t.join();
  if (fatal_) std::rethrow_exception(fatal_);
  if (working_count() == 0) throw_every_device_failed();
  return seconds_since(start);
}

void DevicePool::warm_up(Member& m, const GpuRenderParams& params) {
  // One lockstep work-group's worth (the megakernel's on CPUs) and a wavefront's local size.
  constexpr uint32_t kWarmUpPixels = 64;
  GpuRenderParams p = params;
  p.pixel_begin = 0;
  p.pixel_count = std::min(params.pixel_count, kWarmUpPixels);
  p.sample_begin = 0;
  p.samples_per_pass = 1;
  p.slotted = 0;
  const Clock::time_point start = Clock::now();
  try {
    m.renderer->render_pass(p, nullptr);
    m.share.first_launch_seconds = seconds_since(start);
    m.warm_up_stages = m.renderer->stage_times();
  } catch (const Error& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    retire(m, e.what(), std::current_exception());
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!fatal_) fatal_ = std::current_exception();
  }
}

void DevicePool::run_pass(const GpuRenderParams& params, Film& film, const std::vector<GpuSampleSlot>* slots) {
  const PixelRange all{0, params.pixel_count};
  if (params.slotted) {
    // An adaptive pass may give one pixel several slots, which two devices' ranges can split: the
    // film takes the whole pass in slot order, so that the double sums of such a pixel are added in
    // the same order whatever the split (a pixel of a uniform pass gets one entry and no order).
    std::vector<GpuPixelPass> pass(params.pixel_count);
    std::vector<float> aovs(film.has_aovs() ? size_t(params.pixel_count) * CLPT_AOV_CHANNELS : 0);
    run_pass_part(
        params, all,
        [&](const std::vector<GpuPixelPass>& result, const std::vector<float>& result_aovs, uint32_t slot_begin) {
          std::copy(result.begin(), result.end(), pass.begin() + slot_begin);
          if (!aovs.empty())
            std::copy(result_aovs.begin(), result_aovs.end(), aovs.begin() + long(slot_begin) * CLPT_AOV_CHANNELS);
        },
        slots);
    film.add_pass(pass, 0, params.samples_per_pass, slots);
    if (film.has_aovs()) film.add_aovs(aovs, 0, params.samples_per_pass, slots);
    return;
  }
  const int half = int(params.sample_begin >> CLPT_SAMPLE_STREAM_BIT);
  run_pass_part(params, all,
                [&](const std::vector<GpuPixelPass>& result, const std::vector<float>& aovs, uint32_t pixel_begin) {
                  film.add_pass(result, pixel_begin, params.samples_per_pass, nullptr, half);
                  if (film.has_aovs()) film.add_aovs(aovs, pixel_begin, params.samples_per_pass);
                });
}

bool DevicePool::every_device_failed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return working_count() == 0;
}

void DevicePool::run_pass_part(const GpuRenderParams& params, PixelRange pixels, const PassSink& sink,
                               const std::vector<GpuSampleSlot>* slots) {
  if (params.slotted && (!slots || pixels.begin + pixels.count > slots->size()))
    throw std::logic_error("DevicePool: an adaptive pass without its slots");
  const GpuSampleSlot* slot_data = params.slotted ? slots->data() : nullptr;
  PassState pass(pixels);
  std::vector<Member*> working;
  for (const auto& m : members_)
    if (!m->failed) working.push_back(m.get());
  // Every working device gets its first range of the pass here, in --device order, before any
  // device thread runs. Left to the threads, whether a device took part in a pass depended on how
  // soon its thread reached the queue: a fast device could empty a small pass in its first few
  // launches before a slow device's thread had started (seen with PoCL beside the Oclgrind
  // simulator when the machine was loaded: the simulator traced nothing in 1 of 6 runs). Handed
  // out here, each device starts the pass at once with work in hand, and what it traces follows
  // from the measured rates alone (test_oclgrind.cpp's mixed render relies on that).
  std::vector<Taken> first(working.size());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < working.size() && !pass.queue.empty(); ++i)
      first[i] = take_range(*working[i], pass, params.samples_per_pass);
  }
  // The first working device runs on this thread: a single-device render starts no thread.
  std::vector<std::thread> threads;
  for (size_t i = 1; i < working.size(); ++i)
    threads.emplace_back([&, i] { work(*working[i], params, slot_data, sink, pass, first[i]); });
  if (!working.empty()) work(*working[0], params, slot_data, sink, pass, first[0]);
  for (std::thread& t : threads) t.join();
  if (fatal_) std::rethrow_exception(fatal_);
  if (!pass.queue.empty()) throw_every_device_failed();
  for (Member* m : working) {
    m->last_pass = m->this_pass;
    m->this_pass = {};
  }
}

// One device's loop within a pass: take a range, trace it, add it to the film; until the queue
// is empty and no range is in flight (a range in flight may still come back from a failure).
void DevicePool::work(Member& m, const GpuRenderParams& params, const GpuSampleSlot* slots, const PassSink& sink,
                      PassState& pass, Taken first) {
  try {
    for (;;) {
      Taken taken = std::exchange(first, Taken{});
      if (taken.range.count == 0) {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [&] { return fatal_ || !pass.queue.empty() || pass.in_flight == 0; });
        if (fatal_ || pass.queue.empty()) return;
        taken = take_range(m, pass, params.samples_per_pass);
      }
      const PixelRange range = taken.range;
      const uint64_t launch = taken.launch;
      GpuRenderParams p = params;
      p.pixel_begin = range.begin;
      p.pixel_count = range.count;
      std::vector<GpuPixelPass> result;
      std::vector<float> aovs;  // the first-hit layers' sums, when the kernel has them
      const Clock::time_point start = Clock::now();
      try {
        if (faults_.fails_launch(m.position, launch))
          FaultPlan::throw_injected(CL_OUT_OF_RESOURCES, "clEnqueueNDRangeKernel", m.ctx->where() + " (render_pass)");
        if (const uint64_t ms = faults_.launch_delay_ms(m.position))
          std::this_thread::sleep_for(std::chrono::milliseconds(ms));
        result = m.renderer->render_pass(p, slots ? slots + range.begin : nullptr);
        aovs = m.renderer->aov_sums();
      } catch (const Error& e) {
        std::lock_guard<std::mutex> lock(mutex_);
        --pass.in_flight;
        pass.queue.give_back(range);
        retire(m, e.what(), std::current_exception());
        changed_.notify_all();
        return;
      }
      const double seconds = std::max(1e-9, seconds_since(start));
      apply_perturbation(faults_.channel_factors(m.position), result);
      uint64_t segments = 0;
      for (const GpuPixelPass& px : result) segments += px.segments;
      std::lock_guard<std::mutex> lock(mutex_);
      sink(result, aovs, range.begin);
      const double pixel_samples = double(range.count) * params.samples_per_pass;
      m.launch_rate = pixel_samples / seconds;
      m.this_pass.pixel_samples += pixel_samples;
      m.this_pass.seconds += seconds;
      m.share.paths += uint64_t(range.count) * params.samples_per_pass;
      m.share.segments += segments;
      m.share.busy_seconds += seconds;
      ++m.share.launches;
      --pass.in_flight;
      changed_.notify_all();
    }
  } catch (...) {  // not a device failure (a broken film contract, no memory): stops the render
    std::lock_guard<std::mutex> lock(mutex_);
    if (!fatal_) fatal_ = std::current_exception();
    changed_.notify_all();
  }
}

DevicePool::Taken DevicePool::take_range(Member& m, PassState& pass, uint32_t samples) {
  Taken t;
  t.range = pass.queue.take(range_pixels(m, pass.queue.remaining(), samples));
  m.previous_pixels = t.range.count;
  t.launch = ++m.launches_started;
  ++pass.in_flight;
  return t;
}

uint32_t DevicePool::range_pixels(Member& m, uint32_t remaining, uint32_t samples) const {
  const uint32_t launch =
      next_launch_pixels(m.sizing, remaining, samples, m.launch_rate, m.previous_pixels);
  double mine = 0, all = 0;
  for (const auto& other : members_) {
    if (other->failed) continue;
    Throughput t = other->last_pass;
    t.pixel_samples += other->this_pass.pixel_samples;
    t.seconds += other->this_pass.seconds;
    if (t.rate() <= 0) return launch;  // a device not yet measured: no shares yet
    all += t.rate();
    if (other.get() == &m) mine = t.rate();
  }
  return balanced_range_pixels(launch, remaining, mine / all, m.sizing.first_pixels);
}

void DevicePool::retire(Member& m, const std::string& what, std::exception_ptr error) {
  m.failed = true;
  m.share.failure = what;
  m.error = std::move(error);
  if (working_count() > 0)
    notices_.push_back("device " + std::to_string(m.position) + " (" + m.share.device + ") failed: " + what +
                       "; its work goes to the other devices");
}

void DevicePool::throw_every_device_failed() const {
  if (members_.size() == 1 && members_[0]->error) std::rethrow_exception(members_[0]->error);
  std::string message = "every device failed:";
  for (const auto& m : members_)
    message += "\n  device " + std::to_string(m->position) + " (" + m->share.device + "): " + m->share.failure;
  throw Error(ExitCode::DeviceError, message);
}

size_t DevicePool::working_count() const {
  return size_t(std::count_if(members_.begin(), members_.end(), [](const auto& m) { return !m->failed; }));
}

uint32_t DevicePool::max_samples_per_pass(uint32_t pixel_count) const {
  uint32_t n = UINT32_MAX;
  for (const auto& m : members_)
    if (!m->failed) n = std::min(n, m->renderer->max_samples_per_pass(pixel_count));
  return n;
}

std::vector<std::string> DevicePool::take_notices() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(notices_, {});
}

std::vector<DeviceShare> DevicePool::shares() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<DeviceShare> out;
  for (const auto& m : members_) out.push_back(m->share);
  return out;
}

std::vector<StageTime> DevicePool::stage_times() const {
  std::map<std::string, StageTime> stages;
  for (const auto& m : members_) {
    if (!m->renderer) continue;  // failed its set-up
    for (const StageTime& t : m->renderer->stage_times()) {
      StageTime& sum = stages[t.label];
      sum.label = t.label;
      sum.seconds += t.seconds;
      sum.launches += t.launches;
    }
    for (const StageTime& t : m->warm_up_stages) {  // the passes' only
      StageTime& sum = stages[t.label];
      sum.seconds -= t.seconds;
      sum.launches -= t.launches;
    }
  }
  std::vector<StageTime> out;
  for (auto& entry : stages) out.push_back(entry.second);
  return out;
}

std::shared_ptr<KernelCache> DevicePool::kernel_cache() const {
  for (const auto& m : members_)
    if (m->renderer) return m->ctx->kernel_cache();
  return nullptr;
}

}  // namespace clpt
