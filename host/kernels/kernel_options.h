// The one place that decides how a kernel is specialised for a scene: which features are
// compiled in and the exact build options. `clpt render --explain` prints its answer.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "cl/cl_device.h"
#include "scene/loop_spheres.h"
#include "scene/precision_preset.h"
#include "scene/device_textures.h"
#include "scene/scene.h"

namespace clpt {

// Ray/sphere formula (kernels/intersect.cl; `--intersection` overrides the preset's choice).
//   centre:  textbook, from the sphere's centre: cheapest, and 11% too dark on the book's scene
//   surface: from a surface point s0 and its normal (no radius^2 terms), disc = b'^2 - c'
//   robust:  the surface form with Haines' discriminant r^2 - |l|^2 (exact for far small spheres)
enum class Intersection { Centre = 0, Surface = 1, Robust = 2 };
const char* intersection_name(Intersection intersection);
std::optional<Intersection> parse_intersection(const std::string& name);
// The preset's formula: fast -> surface, robust and double -> robust.
Intersection default_intersection(Precision precision);

// Path estimator (`--estimator`, scene `render.estimator`).
//   book: the book's: no next-event estimation, light only where a path hits an emitter
//   nee:  next-event estimation at every non-specular vertex, MIS (power heuristic) with BSDF hits
enum class Estimator { Book, Nee };
const char* estimator_name(Estimator estimator);
std::optional<Estimator> parse_estimator(const std::string& name);

// The megakernel's loop (kernels/megakernel.cl; `--megakernel-loop`).
//   auto:     lockstep on CPU devices with the fast and robust presets, per path otherwise
//   path:     each work-item loops over its own path's segments
//   lockstep: a work-group's paths advance one segment at a time, together (PoCL vectorises it)
enum class MegakernelLoop { Auto, PerPath, Lockstep };
const char* megakernel_loop_name(MegakernelLoop loop);
// "auto" | "path" | "lockstep"; nullopt otherwise.
std::optional<MegakernelLoop> parse_megakernel_loop(const std::string& name);
// The lockstep work-group size when not given (--local-size): 64 measured fastest on PoCL of
// 32..256 (README "Speed"); small groups lose fewer lanes to paths that ended early.
constexpr uint32_t kDefaultLockstepGroup = 64;
// Work-group size of the lockstep loop for `loop` on this device (local_size: the user's
// --local-size, 0 for none), or 0 for the per-path loop.
uint32_t lockstep_group_for(MegakernelLoop loop, const DeviceInfo& device, size_t local_size);

// The scene-specialised sphere and light loops (CLPT_SPHERE_COUNT, CLPT_LIGHT_COUNT;
// `--scene-loops`). Only a specialised kernel has them; the generic one loops over run-time counts.
//   auto:     unrolled on CPU devices, rolled on GPUs
//   unrolled: straight-line code, which PoCL vectorises across work-items (a loop stops it)
//   rolled:   a loop with a fixed trip count: on a GPU the unrolled spheres' intersections are
//             scheduled side by side and keep their temporaries live together; the loop needs a
//             quarter fewer registers in shading and half in intersection (docs/gpu-compilers.md)
enum class SceneLoops { Auto, Unrolled, Rolled };
const char* scene_loops_name(SceneLoops loops);
// "auto" | "unrolled" | "rolled"; nullopt otherwise.
std::optional<SceneLoops> parse_scene_loops(const std::string& name);
// Whether a kernel for this device unrolls its scene loops.
bool scene_loops_unrolled_for(SceneLoops loops, const DeviceInfo& device);

// How wide PoCL vectorises the kernels on an x86 CPU with AVX-512 (`--cpu-vector-bits`): how many
// work-items one iteration of a vectorised work-item loop handles, set on PoCL's LLVM vectoriser
// (cl/pocl_vectoriser.h).
//   auto: 512 where it can be had (device_takes_512_bit_vectors and the vectoriser reachable),
//         else 256 (measured on AMD EPYC Zen 5, 2026-12-04: 16 lanes ran 1.4-2.3x faster than
//         LLVM's own 8 over the bench's scenes, presets and estimators; docs/performance.md "Width")
//   256:  LLVM's cost model decides: 8 float / 4 double lanes on these CPUs
//   512:  16 lanes (512-bit float vectors; doubles take two registers per value); only on PoCL
//         x86 CPU devices with AVX-512 whose vectoriser is reachable, else a usage error
enum class CpuVectorBits { Auto, Bits256, Bits512 };
const char* cpu_vector_bits_name(CpuVectorBits bits);
// "auto" | "256" | "512"; nullopt otherwise.
std::optional<CpuVectorBits> parse_cpu_vector_bits(const std::string& name);
// Whether this device can be given 512-bit vectors: PoCL's CPU device on an x86-64 host whose
// CPU has AVX-512 (PoCL's CPU device is the host's CPU).
bool device_takes_512_bit_vectors(const DeviceInfo& device);
// The lanes PoCL's vectoriser is set to for this device's kernels (KernelFeatures::
// cpu_vector_lanes): 16 for 512 (and auto where 512 can be had), 0 (LLVM's choice) otherwise.
// Throws Error(Usage) naming --cpu-vector-bits, and why, when 512 is asked of a device that
// cannot have it.
uint32_t cpu_vector_lanes_for(CpuVectorBits bits, const DeviceInfo& device);

// The LLVM CPU PoCL compiles for ("haswell", "skylake-avx512", ...), read from the end of its
// device version ("... HSTR: pthread-x86_64-pc-linux-gnu-haswell"); "" for other devices.
std::string pocl_llvm_cpu(const DeviceInfo& device);
// Whether the device's compiler is known to cost gathers as one scalar load per lane: PoCL's CPU
// device for an x86 LLVM CPU without LLVM 15's fast-gather tuning (Haswell, Broadwell, AMD Zen
// 1-3, generic x86-64; Skylake and later Intel cores and every AVX-512 CPU have it). There it
// keeps the shading scalar unless the kernels avoid indexed reads (CLPT_NO_FAST_GATHER, maths.cl;
// docs/performance.md, "CPUs without fast gathers"). False for every other device.
bool device_lacks_fast_gathers(const DeviceInfo& device);

// How the shading reads the hit sphere's fields (`--sphere-reads`).
//   auto:     selects on devices that lack fast gathers (device_lacks_fast_gathers) with the robust
//             and double presets, else indexed (measured on an AMD EPYC Zen 3, 2026-12-02: robust
//             3.4-5.4x, double 0.8-3.0x, fast 0.8x, whose kernels vectorise only 4 wide with
//             selects; docs/performance.md "CPUs without fast gathers")
//   indexed:  one read per field at the hit's index (a gather across vectorised work-items)
//   selects:  a select per loop sphere and field over reads that are the same for every
//             work-item, and the lockstep state through local memory (CLPT_NO_FAST_GATHER)
enum class SphereReads { Auto, Indexed, Selects };
const char* sphere_reads_name(SphereReads reads);
// "auto" | "indexed" | "selects"; nullopt otherwise.
std::optional<SphereReads> parse_sphere_reads(const std::string& name);
// Whether a kernel for this device reads the hit sphere by selects.
bool sphere_reads_by_select_for(SphereReads reads, const DeviceInfo& device, Precision precision);

// The environment light a kernel compiles (CLPT_HAS_ENVIRONMENT; docs/environment.md):
//   none:     escaping rays are black, no environment code
//   image:    an equirectangular image, looked up by escaping rays and sampled by nee (MIS)
//   constant: one colour, looked up by escaping rays only (BSDF sampling alone is already
//             proportional to a uniform light's integrand): no image reads, no light sample
enum class EnvironmentFeature { None = 0, Image = 1, Constant = 2 };
const char* environment_feature_name(EnvironmentFeature feature);

struct KernelFeatures {
  Precision precision = Precision::Robust;  // CLPT_PRECISION (always fixed: it changes types)
  std::optional<Intersection> intersection;  // CLPT_INTERSECT; unset: default_intersection(precision)
  // Fixed with CLPT_ESTIMATOR unless `generic`, which reads GpuRenderParams.estimator at run time.
  Estimator estimator = Estimator::Book;
  // Fixed with CLPT_SAMPLER unless `generic`: only the chosen sampler's arithmetic is compiled
  // (the grid's camera ray needs no random number at all; jitter's draws no Sobol points).
  Sampler sampler = Sampler::Jitter;
  bool generic = false;           // every feature in; estimator, sampler and counts read at run time
  bool russian_roulette = true;   // CLPT_HAS_RR
  bool phong = true;     // CLPT_HAS_PHONG
  bool glass = true;     // CLPT_HAS_GLASS
  bool mirror = true;    // CLPT_HAS_MIRROR
  // The glTF material and what came with it. A specialised kernel names each of these in its
  // options only when it is on (absent means off there, on in the generic kernel: path.cl,
  // light.cl, camera.cl), so the book's scenes build from exactly the options they had before.
  bool pbr = true;               // CLPT_HAS_PBR: a Pbr material (bsdf_pbr.cl)
  bool pbr_transmission = true;  // CLPT_HAS_PBR_TRANSMISSION: a Pbr material with transmission > 0
  bool pbr_volume = true;        // CLPT_HAS_PBR_VOLUME: such a material with a thickness > 0
  bool point_lights = true;        // CLPT_HAS_POINT_LIGHTS
  bool spot_lights = true;         // CLPT_HAS_SPOT_LIGHTS
  bool directional_lights = true;  // CLPT_HAS_DIRECTIONAL_LIGHTS
  bool orthographic = true;        // CLPT_HAS_ORTHOGRAPHIC: the camera's projection
  // CLPT_HAS_ENVIRONMENT (kernels/environment.cl): what escaping rays see. Named only when not
  // None (absent: none in a specialised kernel; the generic kernel compiles Image).
  EnvironmentFeature environment = EnvironmentFeature::Image;
  bool punctual_lights() const { return point_lights || spot_lights || directional_lights; }
  // Textures (kernels/texture.cl, docs/textures.md), named like the Pbr features only when on:
  // CLPT_HAS_TEXTURES (a textured material on a mesh or a sphere), then what the scene's textures
  // use, as bit masks: CLPT_TEXEL_STORAGES (1 << CLPT_TEXEL_*), CLPT_TEXEL_CHANNELS (1 <<
  // (channels - 1)), CLPT_TEXTURE_WRAPS (1 << CLPT_WRAP_*); CLPT_HAS_NORMAL_MAPS,
  // CLPT_HAS_EMISSION_TEXTURES.
  bool textures = true;
  uint32_t texel_storages = 7;
  // Per material slot (TextureSlot: base colour and alpha, metallic-roughness, normal map,
  // emission) the storages of the images that fill it, a subset of texel_storages, 0 where none
  // does: CLPT_BASE_STORAGES, CLPT_MR_STORAGES, CLPT_NORMAL_STORAGES, CLPT_EMISSION_STORAGES, so
  // that each lookup compiles its own slot's texel reads (kernels/texture.cl).
  std::array<uint32_t, kTextureSlots> slot_storages{7, 7, 7, 7};
  uint32_t texel_channels = 15;
  uint32_t texture_wraps = 7;
  bool normal_maps = true;
  bool emission_textures = true;
  // CLPT_HAS_SPHERE_TEXTURES: a sphere's material is textured (the spherical mapping,
  // docs/textures.md); named only when on, with CLPT_HAS_TEXTURES.
  bool sphere_textures = true;
  // CLPT_HAS_ALPHA (kernels/alpha.cl): a mesh's material is MASK or BLEND with its alpha in effect
  // (scene/device_textures.h, alpha_in_effect); named only when on, and then CLPT_HAS_TEXTURES is
  // on too (the texturing buffer carries the alpha).
  bool alpha = true;
  // CLPT_HAS_VERTEX_COLORS (kernels/vertex_colors.cl): a mesh has vertex colours (glTF COLOR_0);
  // named only when on, and then CLPT_HAS_TEXTURES is on too (the texturing buffer carries them).
  bool vertex_colors = true;
  bool triangles = true;       // CLPT_HAS_TRIANGLES: the scene has meshes
  // CLPT_HAS_TRIANGLE_LIGHTS: next-event estimation samples emitting triangles too, and picks
  // lights by power (nee and a scene with an emitting mesh, or generic).
  bool triangle_lights = true;
  bool spheres_in_bvh = false;  // the spheres are hierarchy primitives (no sphere loop)
  // The scene's triangles when they are few enough for an unrolled loop (loop_triangle_count,
  // scene/loop_spheres.h), else 0; used only where the scene loops are unrolled (triangles_in_loop).
  int loop_triangles = 0;
  // Some triangles are hierarchy primitives whatever the kernel (hierarchy_triangles,
  // scene/loop_spheres.h): with the loop's meshes (loop_meshes) beside them the traversal starts
  // at node 1, the root of their hierarchy (CLPT_BVH_ROOT=1, DeviceScene::loop_triangles).
  bool hierarchy_triangles = true;
  // Whether the kernel may test the meshes of large triangles in its loop beside the hierarchy:
  // only the lockstep megakernel, which runs the loop vectorised apart from the traversal
  // (render_plan.cpp sets false for the others).
  bool loop_beside_hierarchy_allowed = true;
  // CLPT_TRIANGLE_COUNT: the triangles tested in the unrolled loop, no hierarchy: a specialised
  // kernel with unrolled scene loops on PoCL's CPU device with its vectoriser reachable (the 16
  // lanes set, cpu_vector_lanes), whose SLP vectoriser is then held off for it (cl/pocl_vectoriser.h:
  // with it the loop's region runs scalar, 4x slower than the hierarchy). GPUs, and CPUs where
  // PoCL's LLVM cannot be reached, keep the per-path traversal.
  bool triangles_in_loop() const {
    return !generic && triangles && loop_triangles > 0 && !spheres_in_bvh && unroll_scene_loops &&
           (!hierarchy_triangles || loop_beside_hierarchy_allowed) &&
           cpu_vector_lanes > 0;
  }
  // CLPT_WIDE_LEAF_TEST (kernels/bvh.cl): a hierarchy leaf's four triangles tested in one vector
  // operation, on PoCL's CPU device with its vectoriser's width set and a float preset (measured
  // faster there; on a GPU it costs a third more registers in the traversing kernels, and in the
  // double preset PoCL's cold build of a lockstep megakernel 35-45% more time: docs/performance.md);
  // else one at a time from the same leaf block.
  bool wide_leaf_test() const { return cpu_vector_lanes > 0 && precision != Precision::Double; }
  // CLPT_HAS_BVH: traversal compiled (triangles not all in the loop, spheres_in_bvh or generic).
  bool has_hierarchy() const {
    return generic || (triangles && (!triangles_in_loop() || hierarchy_triangles)) || spheres_in_bvh;
  }
  // CLPT_BVH_ROOT=1: the triangle loop and the hierarchy both, the traversal starting at the
  // hierarchy of the triangles not in the loop.
  bool loop_beside_hierarchy() const { return triangles_in_loop() && hierarchy_triangles; }
  int sphere_count = 0;  // CLPT_SPHERE_COUNT when > 0 (a fixed loop, see SceneLoops); 0: read at run time
  int light_count = -1;  // CLPT_LIGHT_COUNT when >= 0: nee's sphere-light loop fixed likewise; -1: run time
  MegakernelLoop megakernel_loop = MegakernelLoop::Auto;  // the request; resolved per device into:
  uint32_t lockstep_group = 0;  // CLPT_LOCKSTEP_GROUP when > 0 (megakernel.cl); 0: per-path loop
  SceneLoops scene_loops = SceneLoops::Auto;  // the request; resolved per device into:
  bool unroll_scene_loops = true;  // false: CLPT_UNROLL_SCENE_LOOPS=0 (a specialised kernel only)
  CpuVectorBits cpu_vector_bits = CpuVectorBits::Auto;  // the request; resolved per device into:
  // Work-items per vectorised loop iteration on PoCL's CPU device when > 0 (cl/pocl_vectoriser.h),
  // with CLPT_CPU_VECTOR_LANES in the build options to key the kernel caches; 0: LLVM's choice.
  uint32_t cpu_vector_lanes = 0;
  SphereReads sphere_reads = SphereReads::Auto;  // the request; resolved per device into:
  // The hit sphere read by selects (sphere_reads_by_select_for): CLPT_NO_FAST_GATHER=1 in a
  // specialised kernel whose spheres are all in the loop.
  bool no_fast_gather = false;
  // CLPT_AOVS=1: paths record the first-hit layers a denoiser takes (albedo, normal, depth;
  // kernels/aov.cl, docs/aovs.md) and the kernels sum them per pixel. Asked for by the render
  // (`--aovs`), not by the scene: off in every kernel, the generic one too, unless asked; named in
  // the build options only when on.
  bool aovs = false;
  // When non-zero, -DCLPT_BUILD_NONCE=n: a source no driver has cached (cold-build timing).
  uint64_t build_nonce = 0;
};

// Only what the scene uses. (Lambertian and emitters are always present.)
KernelFeatures features_for_scene(const Scene& scene, Precision precision = Precision::Robust);

// Throws Error(Usage) when the scene's punctual lights cannot be seen by its estimator: the book
// estimator finds light only where a path hits an emitter, and a delta light is never hit
// (docs/materials.md, "Lights"). Called by plan_render.
void require_estimator_sees_lights(const Scene& scene);

// Every feature compiled in: the generic kernel.
KernelFeatures generic_features(Precision precision = Precision::Robust);

// Whether these features compile the hit sphere's reads as selects (CLPT_NO_FAST_GATHER): asked
// for (no_fast_gather), in a specialised kernel (the loop's count is fixed) whose spheres are all
// in the loop.
bool reads_spheres_by_select(const KernelFeatures& features);

// Whether the sphere loop carries the hit sphere's centre (CLPT_HIT_CENTRE): in the CPU's lockstep
// megakernel whose spheres are all in the unrolled loop (a rolled loop is the GPUs' shape, where
// the carried values cost registers: 110 -> 169 VGPRs on gfx906), unless selects read the hit
// sphere anyway or the intersection is the textbook one. There it replaces the shading's seven gathers of the hit
// sphere's geometry by three selects per sphere (docs/performance.md, "What limits the speed").
bool hit_carries_sphere_centre(const KernelFeatures& features);

// Whether the hit sphere's material is picked by selects over the loop's spheres
// (CLPT_MATERIAL_BY_SELECT): wherever its geometry is (reads_spheres_by_select), and where the
// loop carries its centre (measured faster than the gathers on an AMD Zen 4: docs/performance.md).
bool picks_material_by_select(const KernelFeatures& features);

// Whether one draw serves the scattering of two bounces (CLPT_SCATTER_DRAW_PAIRS, path.cl's
// scatter_draw): where scattering reads only two uniforms, i.e. no glass, no Pbr material (whose
// lobe choice reads u2) and no Russian roulette.
// It changes which random numbers a path uses, so every form, loop and device of one render must
// agree: a specialised kernel fixes it from these features, and the generic kernel reads
// GpuRenderParams.scatter_draw_pairs, which make_params (render_plan.cpp) sets from the scene's.
bool scatter_draws_paired(const KernelFeatures& features);

// Whether the lockstep megakernel evaluates each paired draw once for two segments a step
// (megakernel.cl): with paired draws and unrolled scene loops, no hierarchy, and no triangle loop.
// With one, the step's two segments held four unrolled copies of the loop (each segment's closest
// hit and shadow ray), and PoCL's cold compile of the Cornell box took 12 s; one segment a step
// halves that for 0.985x the paths per CPU-second (docs/performance.md, "Fixed costs"). The
// draws, and so the images, are the same either way. Off, it is named (CLPT_LOCKSTEP_SEGMENT_PAIRS=0).
bool lockstep_pairs_segments(const KernelFeatures& features);

// OpenCL build options for these features.
std::string kernel_build_options(const KernelFeatures& features);

// Human-readable: one line per decision, then the options. The megakernel loop is the device's
// (render_plan.h prints it with the plan).
std::string explain_kernel_options(const KernelFeatures& features);

}  // namespace clpt
