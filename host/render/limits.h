// What clpt accepts, checked before anything is allocated: image size, samples per pixel, sphere
// count and bounces (device-free, `check_scene_limits`), and the device memory the chosen
// execution form would need (`check_device_memory`). Each failure is a clpt::Error whose message
// names the value, the limit and, for memory, the device and both sizes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "render/renderer.h"
#include "scene/scene.h"

namespace clpt {

struct DeviceInfo;

constexpr int kMaxImageSide = 16384;               // pixels, per axis
constexpr uint64_t kMaxImagePixels = 1ull << 26;   // width * height
constexpr uint64_t kMaxSpp = 1ull << 31;           // sample indices are 32-bit on the device
constexpr size_t kMaxSpheres = 4096;
// Triangles over all meshes: their indices are 31-bit in the hierarchy's leaves and signed 32-bit
// in a hit; 2^27 keeps every index (and the 2n - 1 nodes) far from either.
constexpr uint64_t kMaxTriangles = 1ull << 27;
// Device bytes per triangle: GpuTriangle (48) + GpuTriangleShading (112) + at most 2/3 of a 4-wide
// hierarchy node (128 B; 86 rounded up): the collapse (scene/bvh_build.h) gives a node fewer than
// 4 children only when all are leaves, so a tree over n primitives (at most n leaves) has at most
// (2n + 2) / 3 nodes (kMaxBvhNodes) + at most one leaf block (GpuTriangleBlock, 160 B: a leaf's
// triangles four by four, at least one a block).
constexpr uint64_t kDeviceBytesPerTriangle = 48 + 112 + 86 + 160;
constexpr uint64_t kMaxBvhNodes(uint64_t primitives) { return (2 * primitives + 2) / 3; }
constexpr int kMaxBouncesLimit = 1000;
constexpr uint32_t kMaxSamplesPerPass = 4096;  // keeps each pass's float sums exact enough
// kernels/film.cl sums a pass in three levels of blocks of CLPT_FILM_BLOCK = 16 samples, whose
// error bound (about 45 ulps) holds up to 16^3 samples; a larger pass would still be summed, with
// a longer sequential outermost level and a looser bound.
static_assert(kMaxSamplesPerPass <= 16 * 16 * 16, "film.cl's blocked sum has three levels of 16");

// The most bytes of one per-launch buffer on any device (launch_buffer_budget).
constexpr uint64_t kMaxLaunchBufferBytes = uint64_t(256) << 20;

// Bytes one per-launch buffer may take on `device`: min(kMaxLaunchBufferBytes, max allocation / 2). Bounds the
// wavefront's job results (WavefrontRenderer::max_samples_per_pass) and the megakernel's pass
// statistics per launch (so at most budget / 32 pixels per launch).
uint64_t launch_buffer_budget(const DeviceInfo& device);

// Bytes of one job's results (kernels/film.cl): 16, and 28 more with the first-hit layers
// (`aovs`, CLPT_AOVS: kernels/film_aov.cl).
uint32_t result_bytes_per_job(bool aovs);

// The most samples per pass whose job results (result_bytes_per_job per sample of each of
// `pixel_count` pixels) fit launch_buffer_budget(device); at least 1. Both execution forms are
// bounded by it.
uint32_t max_samples_per_pass_for(const DeviceInfo& device, uint32_t pixel_count,
                                  bool aovs = false);  // <= kMaxSamplesPerPass

// Which settings the command line set: a limit they break is a usage error (exit 2) naming the
// option; one the scene file breaks is a scene error (exit 3) naming the file.
struct SettingOrigins {
  bool size_from_command_line = false;    // --width or --height given
  bool spp_from_command_line = false;     // --spp given
  bool bounces_from_command_line = false; // --max-bounces given
};

// Throws Error(Usage or BadScene) when the scene or its settings exceed a limit above.
void check_scene_limits(const Scene& scene, const SettingOrigins& origins = {});

// Device memory an execution form needs for a render, in bytes.
struct MemoryEstimate {
  uint64_t total_bytes = 0;
  uint64_t largest_bytes = 0;  // the largest single buffer
  std::string largest_label;   // its name, as the renderers label it ("job results")
};

// The buffers MegakernelRenderer / WavefrontRenderer allocate for `pixels` pixels and
// `spheres` spheres (paths_in_flight: the wavefront's path slots as planned, render_plan.h): the sphere buffer (96 B each) and pass statistics (32 B per pixel of a
// launch) for both; the wavefront adds paths_in_flight x the bytes of one path slot (the
// buffers of kernels/path_state.h twice and its scratch once, at the double preset's sizes, the
// largest) and job results of result_bytes_per_job per sample of a pass, with
// samples_per_pass as large as it allows (WavefrontRenderer::max_samples_per_pass).
// `triangles` adds the triangle, triangle shading and hierarchy node buffers (the nodes counted at
// their bound of two per primitive, spheres included); `lights` the light list (48 B each);
// `environment_bytes` the environment light's buffer (environment_bytes_of).
// `aovs` (the first-hit layers, CLPT_AOVS): job results of result_bytes_per_job(true), the
// layers' per-pixel sums (28 B per pixel of a launch) and, wavefront, their path-state fields.
MemoryEstimate estimate_device_memory(ExecutionForm form, uint64_t pixels, size_t spheres,
                                      uint32_t paths_in_flight, const DeviceInfo& device,
                                      uint64_t triangles = 0, uint64_t lights = 0, uint64_t environment_bytes = 0,
                                      bool aovs = false);

// Bytes of the scene's environment buffer (types.h GpuEnvironment and 28 B a texel); 0 without one.
uint64_t environment_bytes_of(const Scene& scene);

// Triangles over all of the scene's meshes.
uint64_t triangle_count(const Scene& scene);
// At least the light list's entries (scene/device_scene.h): emitting spheres, the triangles of
// emitting meshes (of which those of zero area get none) and the punctual lights.
uint64_t light_entry_bound(const Scene& scene);

// Throws Error(DeviceError) naming the device and the sizes when `need` exceeds the device's
// global memory or its largest allocation.
void check_device_memory(const MemoryEstimate& need, const DeviceInfo& device);

// "3.2 GiB", "512.0 MiB", "12.0 KiB", "100 B": one decimal, binary units.
std::string format_bytes(uint64_t bytes);

}  // namespace clpt
