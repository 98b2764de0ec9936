#include "render/limits.h"

#include <algorithm>
#include <cstdio>

#include "cl/cl_device.h"
#include "kernels/aov_channels.h"
#include "kernels/path_state.h"
#include "scene/device_scene.h"
#include "util/error.h"

namespace clpt {
namespace {

// Bytes of one path slot: both persistent sets and the scratch set (kernels/path_state.h), with
// `real` fields of the double preset's 8 bytes: the largest, so the estimate holds for every preset.
// `aovs`: the kernel has the first-hit layers' fields (CLPT_AOVS).
constexpr uint64_t path_slot_bytes(bool aovs) {
  uint64_t bytes = 0;
  constexpr uint64_t real_bytes = 8;
#define CLPT_REAL_BYTES real_bytes
#define CLPT_HOST_AOVS aovs
#define CLPT_ADD_STATE(type, name, size, doc) bytes += 2 * (size);
#define CLPT_ADD_SCRATCH(type, name, size, doc) bytes += (size);
  CLPT_PATH_STATE_FIELDS(CLPT_ADD_STATE)
  CLPT_PATH_SCRATCH_FIELDS(CLPT_ADD_SCRATCH)
#undef CLPT_ADD_STATE
#undef CLPT_ADD_SCRATCH
#undef CLPT_HOST_AOVS
#undef CLPT_REAL_BYTES
  return bytes;
}

// Scene-file limits are scene errors (exit 3) naming the file; command-line ones usage errors.
[[noreturn]] void fail_limit(bool from_command_line, const std::string& option, const Scene& scene,
                             const std::string& key, const std::string& message) {
  if (from_command_line) throw Error(ExitCode::Usage, option + ": " + message);
  throw Error(ExitCode::BadScene, scene.file + ": " + key + ": " + message);
}

void add_buffer(MemoryEstimate& e, uint64_t bytes, const char* label) {
  e.total_bytes += bytes;
  if (bytes > e.largest_bytes) {
    e.largest_bytes = bytes;
    e.largest_label = label;
  }
}

}  // namespace

uint64_t launch_buffer_budget(const DeviceInfo& device) {
  const uint64_t cap = kMaxLaunchBufferBytes;
  return device.max_alloc_bytes > 0 ? std::min<uint64_t>(cap, device.max_alloc_bytes / 2) : cap;
}

uint32_t result_bytes_per_job(bool aovs) { return 16u + (aovs ? 4u * CLPT_AOV_CHANNELS : 0u); }

uint32_t max_samples_per_pass_for(const DeviceInfo& device, uint32_t pixel_count, bool aovs) {
  const uint64_t per_sample = result_bytes_per_job(aovs) * uint64_t(std::max(pixel_count, 1u));
  return static_cast<uint32_t>(std::clamp<uint64_t>(launch_buffer_budget(device) / per_sample, 1, kMaxSamplesPerPass));
}

void check_scene_limits(const Scene& scene, const SettingOrigins& origins) {
  const RenderSettings& s = scene.settings;
  const bool size_cli = origins.size_from_command_line;
  const std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
  if (s.width < 1 || s.height < 1 || s.width > kMaxImageSide || s.height > kMaxImageSide)
    fail_limit(size_cli, "--width/--height", scene, "image",
               "the image " + size + " is outside 1.." + std::to_string(kMaxImageSide) + " pixels per side");
  const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
  if (pixels > kMaxImagePixels)
    fail_limit(size_cli, "--width/--height", scene, "image",
               "the image " + size + " has " + std::to_string(pixels) + " pixels; at most " +
                   std::to_string(kMaxImagePixels) + " (2^26) are supported");
  if (s.spp < 1 || uint64_t(s.spp) > kMaxSpp)
    fail_limit(origins.spp_from_command_line, "--spp " + std::to_string(s.spp), scene, "render.spp",
               "samples per pixel must be in [1, " + std::to_string(kMaxSpp) +
                   "] (2^31: sample indices are 32-bit)");
  if (s.max_bounces < 0 || s.max_bounces > kMaxBouncesLimit)
    fail_limit(origins.bounces_from_command_line, "--max-bounces " + std::to_string(s.max_bounces),
               scene, "render.max_bounces",
               "max_bounces must be in [0, " + std::to_string(kMaxBouncesLimit) + "]");
  if (scene.spheres.size() > kMaxSpheres)
    throw Error(ExitCode::BadScene, scene.file + ": sphere: the scene has " +
                                        std::to_string(scene.spheres.size()) + " spheres; at most " +
                                        std::to_string(kMaxSpheres) + " are supported");
  const uint64_t triangles = triangle_count(scene);
  if (triangles > kMaxTriangles)
    throw Error(ExitCode::BadScene, scene.file + ": mesh: the scene's meshes have " + std::to_string(triangles) +
                                        " triangles; at most " + std::to_string(kMaxTriangles) +
                                        " (2^27) are supported");
}

uint64_t light_entry_bound(const Scene& scene) {
  uint64_t n = 0;
  for (const Sphere& s : scene.spheres) n += emits(s.material);
  for (const TriangleMesh& m : scene.meshes)
    if (emits(m.material)) n += m.triangles.size();
  return n + scene.lights.size();
}

uint64_t environment_bytes_of(const Scene& scene) {
  if (!scene.environment) return 0;
  const uint64_t texels = !scene.environment->is_image()
                              ? 1
                              : uint64_t(scene.environment->width) * uint64_t(scene.environment->height);
  // RGB, the density and a (threshold, alias) pair per texel; a pair per row.
  return sizeof(GpuEnvironment) + texels * 6 * 4 + uint64_t(scene.environment->height) * 8;
}

uint64_t triangle_count(const Scene& scene) {
  uint64_t n = 0;
  for (const TriangleMesh& m : scene.meshes) n += m.triangles.size();
  return n;
}

MemoryEstimate estimate_device_memory(ExecutionForm form, uint64_t pixels, size_t spheres,
                                      uint32_t paths_in_flight, const DeviceInfo& device, uint64_t triangles,
                                      uint64_t lights, uint64_t environment_bytes, bool aovs) {
  MemoryEstimate e;
  const uint64_t budget = launch_buffer_budget(device);
  add_buffer(e, uint64_t(spheres) * sizeof(GpuSphere), "spheres");
  add_buffer(e, lights * sizeof(GpuLight), "lights");
  add_buffer(e, environment_bytes, "environment");
  if (triangles > 0) {
    static_assert(sizeof(GpuTriangle) + sizeof(GpuTriangleShading) + (2 * sizeof(GpuBvhNode) + 2) / 3 +
                          sizeof(GpuTriangleBlock) == kDeviceBytesPerTriangle,
                  "kDeviceBytesPerTriangle states the layouts of kernels/types.h");
    add_buffer(e, triangles * sizeof(GpuTriangle), "triangles");
    add_buffer(e, triangles * sizeof(GpuTriangleShading), "triangle shading");
    add_buffer(e, kMaxBvhNodes(triangles + spheres) * sizeof(GpuBvhNode) + triangles * sizeof(GpuTriangleBlock),
               "hierarchy nodes and leaf triangles");
  }
  // Both forms keep result_bytes_per_job per sample of a launch (job results) and 32 B per pixel of a launch (pass
  // statistics). Wavefront launches cover the whole image; megakernel launches at most budget / 32
  // pixels (pass_loop.cpp).
  uint64_t launch_pixels = pixels;
  if (form == ExecutionForm::Wavefront) {
    e.total_bytes += uint64_t(paths_in_flight) * path_slot_bytes(aovs);  // 35 buffers of paths x 4 B: none the largest
  } else {
    launch_pixels = std::min<uint64_t>(pixels, std::max<uint64_t>(1, budget / sizeof(GpuPixelPass)));
  }
  add_buffer(e, launch_pixels * sizeof(GpuPixelPass), "pass statistics");
  if (aovs) add_buffer(e, launch_pixels * 4 * CLPT_AOV_CHANNELS, "first-hit layer sums");
  const uint64_t samples = std::min<uint64_t>(
      max_samples_per_pass_for(device, uint32_t(std::min<uint64_t>(pixels, UINT32_MAX)), aovs), kMaxSamplesPerPass);
  add_buffer(e, launch_pixels * samples * result_bytes_per_job(aovs), "job results");
  return e;
}

void check_device_memory(const MemoryEstimate& need, const DeviceInfo& device) {
  const std::string hint = " (use a smaller image, fewer --paths-in-flight, or another --device)";
  if (device.max_alloc_bytes > 0 && need.largest_bytes > device.max_alloc_bytes)
    throw Error(ExitCode::DeviceError, "buffer '" + need.largest_label + "' would be " +
                                           format_bytes(need.largest_bytes) + " but device '" +
                                           device.name + "' allows at most " +
                                           format_bytes(device.max_alloc_bytes) + " per allocation" + hint);
  if (device.global_mem_bytes > 0 && need.total_bytes > device.global_mem_bytes)
    throw Error(ExitCode::DeviceError, "render needs " + format_bytes(need.total_bytes) + " on device '" +
                                           device.name + "' but it has " +
                                           format_bytes(device.global_mem_bytes) + hint);
}

std::string format_bytes(uint64_t bytes) {
  static const char* const units[] = {"KiB", "MiB", "GiB", "TiB"};
  if (bytes < 1024) return std::to_string(bytes) + " B";
  double value = double(bytes) / 1024;
  int unit = 0;
  while (value >= 1024 && unit < 3) {
    value /= 1024;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

}  // namespace clpt
