#include "render/rank_pass.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "kernels/aov_channels.h"
#include "render/device_pool.h"
#include "render/render_plan.h"
#include "render/render_request.h"
#include "util/byte_buffer.h"
#include "util/clock.h"

namespace clpt {
namespace {

// What rank 0 sends at the start of each round of a pass.
enum class Round : uint8_t { Trace = 0, PassDone = 1, EveryRankFailed = 2 };

std::string join(const std::vector<std::string>& parts, const char* separator) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}

// The build options a kernel of this plan would have on any device: the per-device choices
// (megakernel loop, scene loops, CPU vector width, hit sphere reads) set to one value.
std::string device_independent_options(KernelFeatures features) {
  features.megakernel_loop = MegakernelLoop::Auto;
  features.lockstep_group = 0;
  features.scene_loops = SceneLoops::Auto;
  features.unroll_scene_loops = true;
  features.cpu_vector_bits = CpuVectorBits::Auto;
  features.cpu_vector_lanes = 0;
  features.sphere_reads = SphereReads::Auto;
  features.no_fast_gather = false;
  features.build_nonce = 0;
  return kernel_build_options(features);
}

}  // namespace

std::vector<std::string> render_identity(const RenderRequest& request, const RenderPlan& plan) {
  const Scene& scene = request.scene;
  const RenderSettings& s = scene.settings;
  std::vector<std::string> id = {
      std::string("clpt version: ") + CLPT_VERSION,
      "scene file hash (FNV-1a 64): " + scene.file_hash,
      "image: " + std::to_string(plan.width) + "x" + std::to_string(plan.height),
      "samples per pixel: " + std::to_string(plan.target_spp),
      "time limit (s): " + std::to_string(plan.time_limit_s),
      "target error: " + std::to_string(plan.target_error),
      "seed: " + std::to_string(s.seed),
      std::string("sampler: ") + sampler_name(s.sampler),
      std::string("adaptive sampling: ") + (plan.adaptive ? "on" : "off"),
      "max bounces: " + std::to_string(s.max_bounces),
      "estimator: " + s.estimator,
      "rr from: " + std::to_string(s.rr_from),
      "light sampling: " + s.light_sampling,
      std::string("precision: ") + precision_name(plan.precision),
  };
  for (size_t i = 0; i < scene.meshes.size(); ++i)
    id.push_back("mesh " + std::to_string(i) + " file hash (FNV-1a 64): " + scene.meshes[i].file_hash);
  if (!plan.devices.empty())
    id.push_back("kernel build options: " + device_independent_options(plan.devices[0].features));
  return id;
}

void check_ranks_agree(RankGroup& group, const std::vector<std::string>& identity) {
  ByteWriter mine;
  mine.put(group.host()).put(uint64_t(identity.size()));
  for (const std::string& line : identity) mine.put(line);
  const std::vector<std::vector<uint8_t>> all = group.gather(mine.bytes());
  ByteWriter verdict;
  if (group.coordinator()) {
    const std::string host0 = group.host();
    std::string message;
    for (int r = 1; r < group.size() && message.empty(); ++r) {
      ByteReader in(all[size_t(r)]);
      const std::string host = in.get_string();
      std::vector<std::string> theirs(size_t(in.get<uint64_t>()));
      for (std::string& line : theirs) line = in.get_string();
      for (size_t i = 0; i < std::max(theirs.size(), identity.size()) && message.empty(); ++i) {
        const std::string here = i < identity.size() ? identity[i] : "(nothing)";
        const std::string there = i < theirs.size() ? theirs[i] : "(nothing)";
        if (here != there)
          message = rank_label(group, r, host) + " does not render what rank 0 (host " + host0 +
                    ") renders: rank " + std::to_string(r) + " has '" + there + "', rank 0 '" + here +
                    "'; every rank must load the same scene with the same options";
      }
    }
    verdict.put(message);
  }
  group.broadcast(verdict.bytes());
  ByteReader in(verdict.bytes());
  const std::string message = in.get_string();
  if (!message.empty()) throw JobError(ExitCode::Usage, message);
}

std::vector<PixelRange> split_pixels_by_weight(PixelRange pixels, const std::vector<double>& weights) {
  std::vector<PixelRange> parts(weights.size(), PixelRange{pixels.begin, 0});
  double total = 0;
  size_t last = weights.size();
  for (size_t i = 0; i < weights.size(); ++i)
    if (weights[i] > 0) {
      total += weights[i];
      last = i;
    }
  if (last == weights.size()) return parts;
  uint32_t next = pixels.begin;
  const uint32_t end = pixels.begin + pixels.count;
  double cumulative = 0;
  for (size_t i = 0; i <= last; ++i) {
    parts[i].begin = next;
    if (weights[i] <= 0) continue;
    cumulative += weights[i];
    const uint32_t stop = i == last ? end
                                    : std::min(end, pixels.begin + uint32_t(double(pixels.count) * (cumulative / total)));
    parts[i].count = stop - next;
    next = stop;
  }
  for (size_t i = last + 1; i < parts.size(); ++i) parts[i].begin = end;
  return parts;
}

RankPassTracer::RankPassTracer(RankGroup& group, DevicePool* pool, const std::string& failure,
                               uint32_t image_pixels, FaultPlan faults, const std::atomic<bool>* interrupt)
    : group_(group), pool_(pool), faults_(std::move(faults)), interrupt_(interrupt) {
  mine_.rank = group.rank();
  mine_.host = group.host();
  mine_.failure = failure;
  if (pool_) {
    std::vector<std::string> labels;
    for (const DeviceShare& d : pool_->shares())
      if (d.built) labels.push_back(d.device);
    mine_.devices = join(labels, " + ");
  }
  ByteWriter hello;
  hello.put(mine_.host).put(uint8_t(pool_ != nullptr)).put(failure);
  hello.put(pool_ ? pool_->max_samples_per_pass(image_pixels) : UINT32_MAX);
  const std::vector<std::vector<uint8_t>> all = group.gather(hello.bytes());
  ByteWriter answer;
  if (group.coordinator()) {
    std::string failures;
    for (int r = 0; r < group.size(); ++r) {
      ByteReader in(all[size_t(r)]);
      hosts_.push_back(in.get_string());
      working_.push_back(in.get<uint8_t>() != 0);
      const std::string why = in.get_string();
      const uint32_t max_samples = in.get<uint32_t>();
      rates_.push_back(0);
      failures_.push_back(why);
      if (working_.back()) {
        max_samples_per_pass_ = std::min(max_samples_per_pass_, max_samples);
      } else {
        failures += "\n  " + rank_label(group, r, hosts_.back()) + ": " + why;
        notices_.push_back(rank_label(group, r, hosts_.back()) + " failed: " + why + "; its work goes to the other ranks");
      }
    }
    const bool any = std::count(working_.begin(), working_.end(), true) > 0;
    answer.put(uint8_t(any)).put(max_samples_per_pass_).put(any ? std::string() : "every rank failed:" + failures);
  }
  group.broadcast(answer.bytes());
  ByteReader in(answer.bytes());
  const bool any = in.get<uint8_t>() != 0;
  max_samples_per_pass_ = in.get<uint32_t>();
  const std::string message = in.get_string();
  if (!any) {
    if (!group.coordinator()) notices_.clear();
    throw JobError(ExitCode::DeviceError, message);
  }
}

void RankPassTracer::share(PassDecision& d) {
  ByteWriter out;
  if (group_.coordinator()) out.put(d);
  group_.broadcast(out.bytes());
  ByteReader in(out.bytes());
  d = in.get<PassDecision>();
  if (d.stop() || !faults_.exits_at_pass(++passes_started_)) return;
  std::fprintf(stderr, "clpt: %s: exits at pass %llu, as CLPT_INJECT_FAULT asks\n",
               rank_label(group_, group_.rank(), mine_.host).c_str(), (unsigned long long)passes_started_);
  std::fflush(stderr);
  std::_Exit(1);
}

RankPassTracer::PartResult RankPassTracer::trace_part(const GpuRenderParams& pass, PixelRange part,
                                                      const std::vector<GpuSampleSlot>* slots) {
  PartResult r;
  if (part.count > 0 && pool_) {
    r.pixels.resize(part.count);
    const Clock::time_point start = Clock::now();
    try {
      pool_->run_pass_part(pass, part, [&](const std::vector<GpuPixelPass>& result, const std::vector<float>& aovs,
                                           uint32_t pixel_begin) {
        std::copy(result.begin(), result.end(), r.pixels.begin() + (pixel_begin - part.begin));
        if (aovs.empty()) return;  // no first-hit layers in the kernel
        r.aovs.resize(size_t(part.count) * CLPT_AOV_CHANNELS);
        std::copy(aovs.begin(), aovs.end(), r.aovs.begin() + long(pixel_begin - part.begin) * CLPT_AOV_CHANNELS);
      }, slots);
    } catch (const Error& e) {
      if (!pool_->every_device_failed()) throw;  // not a device failure: the job stops
      r.ok = false;
      r.failure = e.what();
      r.pixels.clear();
      r.aovs.clear();
      mine_.failure = r.failure;
      pool_ = nullptr;  // takes no part in later passes (rank 0 gives it none)
    }
    r.seconds = std::max(1e-9, seconds_since(start));
    mine_.busy_seconds += r.seconds;
    if (r.ok) mine_.paths += uint64_t(part.count) * pass.samples_per_pass;
  }
  r.interrupted = interrupt_ && interrupt_->load(std::memory_order_relaxed);
  return r;
}

void RankPassTracer::trace(const GpuRenderParams& pass, Film& film, const std::vector<GpuSampleSlot>* slots) {
  std::vector<GpuSampleSlot> received;  // an adaptive pass's slots, as rank 0 sent them
  if (pass.slotted) {
    ByteWriter table;
    if (group_.coordinator()) table.put_array(*slots);
    group_.broadcast(table.bytes());
    ByteReader in(table.bytes());
    received = in.get_array<GpuSampleSlot>();
    slots = &received;
  } else {
    slots = nullptr;
  }
  const int half = int(pass.sample_begin >> CLPT_SAMPLE_STREAM_BIT);
  std::vector<PixelRange> left;  // rank 0: pixels of the pass not traced yet
  if (group_.coordinator()) left.push_back(PixelRange{0, pass.pixel_count});
  for (;;) {
    ByteWriter order;
    std::vector<PixelRange> parts;
    if (group_.coordinator()) {
      const bool any = std::count(working_.begin(), working_.end(), true) > 0;
      if (left.empty()) {
        order.put(Round::PassDone);
      } else if (!any) {
        std::string failures;
        for (size_t r = 0; r < hosts_.size(); ++r)
          failures += "\n  " + rank_label(group_, int(r), hosts_[r]) + ": " + failures_[r];
        order.put(Round::EveryRankFailed).put("every rank failed:" + failures);
      } else {
        // Weights: the measured throughputs, or equal shares while a working rank is unmeasured.
        bool measured = true;
        for (size_t r = 0; r < working_.size(); ++r)
          if (working_[r] && rates_[r] <= 0) measured = false;
        std::vector<double> weights(working_.size(), 0.0);
        for (size_t r = 0; r < working_.size(); ++r)
          if (working_[r]) weights[r] = measured ? rates_[r] : 1.0;
        parts = split_pixels_by_weight(left.back(), weights);
        left.pop_back();
        order.put(Round::Trace).put_array(parts);
      }
    }
    group_.broadcast(order.bytes());
    ByteReader in(order.bytes());
    const Round round = in.get<Round>();
    if (round == Round::PassDone) return;
    if (round == Round::EveryRankFailed) throw JobError(ExitCode::DeviceError, in.get_string());
    parts = in.get_array<PixelRange>();
    const PixelRange part = parts[size_t(group_.rank())];
    const PartResult mine = trace_part(pass, part, slots);
    ByteWriter reply;
    reply.put(uint8_t(mine.ok)).put(uint8_t(mine.interrupted)).put(mine.seconds).put(mine.failure).put_array(mine.pixels).put_array(mine.aovs);
    const std::vector<std::vector<uint8_t>> all = group_.gather(reply.bytes());
    if (!group_.coordinator()) continue;
    // Rank order: which rank's part enters the film first changes no pixel (the parts are
    // disjoint), but a fixed order keeps the film's bookkeeping the same from run to run.
    for (size_t r = 0; r < all.size(); ++r) {
      ByteReader from(all[r]);
      const bool ok = from.get<uint8_t>() != 0;
      if (from.get<uint8_t>() != 0 && r != 0) others_interrupted_ = true;
      const double seconds = from.get<double>();
      const std::string failure = from.get_string();
      const std::vector<GpuPixelPass> pixels = from.get_array<GpuPixelPass>();
      const std::vector<float> aovs = from.get_array<float>();  // the first-hit layers' sums, or none
      if (parts[r].count == 0) continue;
      if (!ok) {
        working_[r] = false;
        failures_[r] = failure;
        left.push_back(parts[r]);
        notices_.push_back(rank_label(group_, int(r), hosts_[r]) + " failed: " + failure +
                           "; its work goes to the other ranks");
        continue;
      }
      if (pixels.size() != parts[r].count)
        throw std::logic_error("RankPassTracer: a rank sent " + std::to_string(pixels.size()) + " pixels for a part of " +
                               std::to_string(parts[r].count));
      film.add_pass(pixels, parts[r].begin, pass.samples_per_pass, slots, half);
      if (film.has_aovs()) {
        if (aovs.size() != size_t(parts[r].count) * CLPT_AOV_CHANNELS)
          throw std::logic_error("RankPassTracer: a rank sent no first-hit layers for its part");
        film.add_aovs(aovs, parts[r].begin, pass.samples_per_pass, slots);
      }
      rates_[r] = double(parts[r].count) * pass.samples_per_pass / seconds;
    }
  }
}

std::vector<std::string> RankPassTracer::take_notices() {
  std::vector<std::string> out = std::exchange(notices_, {});
  if (pool_)
    for (const std::string& notice : pool_->take_notices())
      out.push_back(rank_label(group_, group_.rank(), mine_.host) + ": " + notice);
  return out;
}

std::vector<RankShare> RankPassTracer::gather_shares() {
  ByteWriter w;
  w.put(mine_.host).put(mine_.devices).put(mine_.paths).put(mine_.busy_seconds).put(mine_.failure);
  const std::vector<std::vector<uint8_t>> all = group_.gather(w.bytes());
  std::vector<RankShare> shares;
  for (size_t r = 0; r < all.size(); ++r) {
    ByteReader in(all[r]);
    RankShare s;
    s.rank = int(r);
    s.host = in.get_string();
    s.devices = in.get_string();
    s.paths = in.get<uint64_t>();
    s.busy_seconds = in.get<double>();
    s.failure = in.get_string();
    shares.push_back(s);
  }
  return shares;
}

}  // namespace clpt
