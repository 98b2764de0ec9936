#include "render/device_pool.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <thread>
#include <utility>

#include "cl/cl_context.h"
#include "cl/cl_error.h"
#include "render/limits.h"
#include "render/wavefront_renderer.h"
#include "util/clock.h"

namespace clpt {
namespace {

// When several devices share a pass, a range of the wavefront (which needs no watchdog bound)
// aims at a quarter of the pass loop's 0.5 s pass: enough ranges per pass to balance, few enough
// that each fills the device's paths in flight.
constexpr double kSharedRangeTargetS = 0.125;

// Pixel-samples traced and the wall time they took.
struct Throughput {
  double pixel_samples = 0;
  double seconds = 0;
  double rate() const { return seconds > 0 ? pixel_samples / seconds : 0; }
};

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
  // to follow a change of load, long enough to forget the first launch's kernel compilation.
  Throughput last_pass, this_pass;
  uint64_t launches_started = 0;
  bool failed = false;
  std::exception_ptr error;
  DeviceShare share;
};

struct DevicePool::PassState {
  explicit PassState(uint32_t pixels) : queue(pixels) {}
  PixelRangeQueue queue;
  int in_flight = 0;  // ranges taken and not yet added or given back
};

DevicePool::DevicePool(const std::vector<DeviceInfo>& devices, const PoolSettings& settings)
    : faults_(settings.faults) {
  for (size_t i = 0; i < devices.size(); ++i) {
    members_.push_back(std::make_unique<Member>());
    members_.back()->position = i;
    members_.back()->info = devices[i];
    members_.back()->share.device = devices[i].label();
  }
  std::vector<std::thread> threads;
  for (size_t i = 1; i < members_.size(); ++i)
    threads.emplace_back([this, &settings, i] { build(*members_[i], settings); });
  build(*members_[0], settings);
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

void DevicePool::build(Member& m, const PoolSettings& settings) {
  try {
    m.share.form = settings.form.value_or(default_form_for(m.info));
    if (faults_.fails_build(m.position))
      FaultPlan::throw_injected(CL_BUILD_PROGRAM_FAILURE, "clBuildProgram", m.info.label());
    check_precision_supported(settings.features.precision, m.info);
    m.ctx = std::make_unique<DeviceContext>(m.info);
    if (settings.use_kernel_cache) m.ctx->use_default_kernel_cache();
    m.share.device = m.ctx->where();
    check_device_memory(estimate_device_memory(m.share.form, settings.image_pixels,
                                               settings.scene->spheres.size(), settings.paths_in_flight, m.info),
                        m.info);
    m.renderer = make_renderer(m.share.form, *m.ctx, *settings.scene, settings.features,
                               settings.paths_in_flight, settings.local_size);
    m.share.build_seconds = m.renderer->build_seconds();
    // Launch sizing: the megakernel's launches are watchdog-sized (--launch-ms); a pass shared by
    // several devices is cut into throughput-sized ranges whatever the form; otherwise the
    // wavefront takes a whole pass in one launch (its launches are bounded by paths in flight).
    const bool megakernel_split = m.share.form == ExecutionForm::Megakernel && settings.launch_target_s > 0;
    m.sizing.target_s = megakernel_split ? settings.launch_target_s : 0;
    if (!megakernel_split && members_.size() > 1) m.sizing.target_s = kSharedRangeTargetS;
    m.sizing.first_pixels = std::clamp(settings.image_pixels / 64, 1u, 4096u);
    m.sizing.max_pixels =
        uint32_t(std::clamp<uint64_t>(launch_buffer_budget(m.info) / sizeof(GpuPixelPass), 1, UINT32_MAX));
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

void DevicePool::run_pass(const GpuRenderParams& params, Film& film) {
  PassState pass(params.pixel_count);
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
    threads.emplace_back([&, i] { work(*working[i], params, film, pass, first[i]); });
  if (!working.empty()) work(*working[0], params, film, pass, first[0]);
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
void DevicePool::work(Member& m, const GpuRenderParams& params, Film& film, PassState& pass, Taken first) {
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
      const Clock::time_point start = Clock::now();
      try {
        if (faults_.fails_launch(m.position, launch))
          FaultPlan::throw_injected(CL_OUT_OF_RESOURCES, "clEnqueueNDRangeKernel", m.ctx->where() + " (render_pass)");
        result = m.renderer->render_pass(p);
      } catch (const Error& e) {
        std::lock_guard<std::mutex> lock(mutex_);
        --pass.in_flight;
        pass.queue.give_back(range);
        retire(m, e.what(), std::current_exception());
        changed_.notify_all();
        return;
      }
      const double seconds = std::max(1e-9, seconds_since(start));
      uint64_t segments = 0;
      for (const GpuPixelPass& px : result) segments += px.segments;
      std::lock_guard<std::mutex> lock(mutex_);
      film.add_pass(result, range.begin, params.samples_per_pass);
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

void DevicePool::fill_report(RenderReport& report) const {
  std::map<std::string, StageTime> stages;
  report.device.clear();
  report.launches = 0;
  report.devices.clear();
  bool first = true;
  for (const auto& m : members_) {
    report.devices.push_back(m->share);
    report.launches += m->share.launches;
    if (!m->renderer) continue;  // failed its set-up
    if (!report.device.empty()) report.device += " + ";
    report.device += m->share.device;
    report.build_seconds = std::max(first ? 0.0 : report.build_seconds, m->share.build_seconds);
    for (const StageTime& t : m->renderer->stage_times()) {
      StageTime& sum = stages[t.label];
      sum.label = t.label;
      sum.seconds += t.seconds;
      sum.launches += t.launches;
    }
    if (!first) continue;
    first = false;  // the first device built gives the form, options, cache and paths in flight
    report.form = m->share.form;
    report.build_options = m->renderer->build_options();
    report.kernel_cache = m->ctx->kernel_cache();
    if (auto* wavefront = dynamic_cast<WavefrontRenderer*>(m->renderer.get()))
      report.paths_in_flight = wavefront->paths_in_flight();
  }
  report.stage_times.clear();
  for (auto& entry : stages) report.stage_times.push_back(entry.second);
}

}  // namespace clpt
