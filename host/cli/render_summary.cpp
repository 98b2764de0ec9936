#include "cli/render_summary.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "cl/kernel_cache.h"

namespace clpt {
namespace {

// Several devices: each one's share of the samples, its own paths/s over the time it was busy,
// and the combined rate over the passes' time.
void print_device_shares(const RenderReport& r) {
  const double total = std::max<double>(1, double(r.paths));
  const double passes = std::max(1e-9, r.pass_seconds);
  for (size_t i = 0; i < r.devices.size(); ++i) {
    const DeviceShare& d = r.devices[i];
    std::printf("  device %zu %s, %s: %5.1f%% of the samples, %.2f M paths/s, busy %.2f s (%.0f%% of the passes), "
                "%llu launches%s\n",
                i, d.device.c_str(), execution_form_name(d.form), 100.0 * double(d.paths) / total,
                double(d.paths) / std::max(1e-9, d.busy_seconds) * 1e-6, d.busy_seconds,
                100.0 * d.busy_seconds / passes, (unsigned long long)d.launches,
                d.failure.empty() ? "" : " (failed; its work went to the others)");
  }
  std::printf("  combined: %.2f M paths/s on %zu devices\n", double(r.paths) / passes * 1e-6, r.devices.size());
}

// An MPI job: each rank's host, devices, share of the samples, its own paths/s over the time it
// was busy, and the job's combined rate over the passes' time.
void print_rank_shares(const RenderReport& r) {
  const double total = std::max<double>(1, double(r.paths));
  const double passes = std::max(1e-9, r.pass_seconds);
  for (const RankShare& s : r.ranks)
    std::printf("  rank %d on %s, %s: %5.1f%% of the samples, %.2f M paths/s, busy %.2f s (%.0f%% of the passes)%s\n",
                s.rank, s.host.c_str(), s.devices.empty() ? "no device" : s.devices.c_str(),
                100.0 * double(s.paths) / total, double(s.paths) / std::max(1e-9, s.busy_seconds) * 1e-6,
                s.busy_seconds, 100.0 * s.busy_seconds / passes,
                s.failure.empty() ? "" : " (failed; its work went to the others)");
  std::printf("  combined: %.2f M paths/s on %zu ranks\n", double(r.paths) / passes * 1e-6, r.ranks.size());
}

}  // namespace

RenderTimeSplit render_time_split(const RenderReport& r, const RenderCommandTimes& t) {
  RenderTimeSplit s;
  s.wall = seconds_since(t.start);
  s.scene_load = t.scene_load;
  s.image_load = t.image_load;
  s.resume_load = t.resume_load;
  s.discovery = r.discovery_seconds;
  s.convert = r.convert_seconds;
  s.kernel_build = r.build_seconds;
  s.first_launch = r.first_launch_seconds;
  s.passes = r.pass_seconds;
  s.output = t.output;
  s.other = s.wall - (s.scene_load + s.image_load + s.resume_load + s.discovery + s.convert + s.kernel_build + s.first_launch +
                      s.passes + s.output);
  return s;
}

const char* kernel_build_source(const RenderReport& r) {
  return r.kernel_cache && r.kernel_cache->hits() > 0 ? "clpt cache hit" : "compiled";
}

void print_render_summary(const Scene& scene, const RenderReport& r) {
  const double passes = std::max(1e-9, r.pass_seconds);
  // Megakernel passes are split into watchdog-sized launches (--launch-ms): show how many (this
  // process's only, so not for an MPI job).
  const std::string launches = r.form == ExecutionForm::Megakernel && r.ranks.size() <= 1
                                   ? " in " + std::to_string(r.launches) + " launches"
                                   : "";
  const std::string where = r.ranks.size() > 1 ? std::to_string(r.ranks.size()) + " MPI ranks" : r.device;
  std::printf("rendered %s: %dx%d, %llu spp, %d passes%s, %s, %s, estimator %s, on %s\n", scene.file.c_str(),
              scene.settings.width, scene.settings.height, (unsigned long long)r.spp, r.passes,
              launches.c_str(), execution_form_name(r.form), precision_name(r.precision),
              scene.settings.estimator.c_str(), where.c_str());
  std::printf("  passes %.3f s (their launches and the waits for them): %.2f M paths/s, %.2f M ray segments/s "
              "(%.2f segments/path)\n",
              r.pass_seconds, double(r.paths) / passes * 1e-6, double(r.segments) / passes * 1e-6,
              r.paths ? double(r.segments) / double(r.paths) : 0.0);
  if (!r.stage_times.empty()) {
    std::printf("  device time per stage:");
    for (const StageTime& t : r.stage_times)
      std::printf(" %s %.3f s (%llu launches);", t.label.c_str(), t.seconds, (unsigned long long)t.launches);
    std::printf(" %u paths in flight\n", r.paths_in_flight);
  }
  if (r.estimate.valid)
    std::printf("  estimated relative error %.2f%% (RMSE over the image's mean; upper estimate, %llu+%llu spp "
                "halves)%s%s\n",
                100 * r.estimate.relative_rmse_upper, (unsigned long long)r.estimate.half_spp[0],
                (unsigned long long)r.estimate.half_spp[1], r.stop != StopReason::None ? "; stopped at the " : "",
                r.stop != StopReason::None ? stop_reason_name(r.stop) : "");
  if (r.dropped)
    std::printf("  dropped %llu samples with NaN/Inf radiance\n", (unsigned long long)r.dropped);
  if (r.devices.size() > 1) print_device_shares(r);
  if (r.ranks.size() > 1) print_rank_shares(r);
}

void print_render_times(const RenderReport& r, const RenderCommandTimes& t) {
  const RenderTimeSplit s = render_time_split(r, t);
  char image_text[48] = "";
  if (s.image_load > 0) std::snprintf(image_text, sizeof image_text, " + image load %.3f s", s.image_load);
  char resume_text[48] = "";
  if (s.resume_load > 0) std::snprintf(resume_text, sizeof resume_text, " + checkpoint load %.3f s", s.resume_load);
  std::printf("  wall %.3f s = scene load %.3f s%s%s + device discovery %.3f s + conversion and hierarchy %.3f s + "
              "kernel build %.3f s (%s) + first launch %.3f s + passes %.3f s + output writing %.3f s + other %.3f s "
              "(contexts, uploads, work between passes)\n",
              s.wall, s.scene_load, image_text, resume_text, s.discovery, s.convert, s.kernel_build, kernel_build_source(r),
              s.first_launch, s.passes, s.output, s.other);
}

}  // namespace clpt
