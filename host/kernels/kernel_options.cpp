#include "kernels/kernel_options.h"

#include <algorithm>
#include <initializer_list>
#include <sstream>

#include "cl/pocl_vectoriser.h"
#include "scene/device_scene.h"
#include "scene/device_textures.h"
#include "util/error.h"

namespace clpt {

const char* intersection_name(Intersection intersection) {
  switch (intersection) {
    case Intersection::Centre: return "centre";
    case Intersection::Surface: return "surface";
    default: return "robust";
  }
}

std::optional<Intersection> parse_intersection(const std::string& name) {
  if (name == "centre") return Intersection::Centre;
  if (name == "surface") return Intersection::Surface;
  if (name == "robust") return Intersection::Robust;
  return std::nullopt;
}

Intersection default_intersection(Precision precision) {
  return precision == Precision::Fast ? Intersection::Surface : Intersection::Robust;
}

const char* environment_feature_name(EnvironmentFeature feature) {
  switch (feature) {
    case EnvironmentFeature::Image: return "image";
    case EnvironmentFeature::Constant: return "constant";
    default: return "none";
  }
}

const char* estimator_name(Estimator estimator) { return estimator == Estimator::Nee ? "nee" : "book"; }

std::optional<Estimator> parse_estimator(const std::string& name) {
  if (name == "book") return Estimator::Book;
  if (name == "nee") return Estimator::Nee;
  return std::nullopt;
}

const char* megakernel_loop_name(MegakernelLoop loop) {
  switch (loop) {
    case MegakernelLoop::PerPath: return "path";
    case MegakernelLoop::Lockstep: return "lockstep";
    default: return "auto";
  }
}

std::optional<MegakernelLoop> parse_megakernel_loop(const std::string& name) {
  if (name == "auto") return MegakernelLoop::Auto;
  if (name == "path") return MegakernelLoop::PerPath;
  if (name == "lockstep") return MegakernelLoop::Lockstep;
  return std::nullopt;
}

// CPUs get the lockstep loop with every preset: PoCL vectorises only loop-free code across
// work-items, so the per-path loop runs scalar (the lockstep one measured 4.9-6.4x faster with
// robust on the three book scenes with either estimator, 5x with fast, and 2.3-3.3x with double
// once its code was vectorised: docs/performance.md, "Presets"). GPUs mask diverged lanes in
// hardware and need no barrier per segment; no GPU has measured either loop yet.
uint32_t lockstep_group_for(MegakernelLoop loop, const DeviceInfo& device, size_t local_size) {
  const bool lockstep = loop == MegakernelLoop::Lockstep || (loop == MegakernelLoop::Auto && device.is_cpu);
  if (!lockstep) return 0;
  return static_cast<uint32_t>(local_size ? local_size : kDefaultLockstepGroup);
}

const char* cpu_vector_bits_name(CpuVectorBits bits) {
  switch (bits) {
    case CpuVectorBits::Bits256: return "256";
    case CpuVectorBits::Bits512: return "512";
    default: return "auto";
  }
}

std::optional<CpuVectorBits> parse_cpu_vector_bits(const std::string& name) {
  if (name == "auto") return CpuVectorBits::Auto;
  if (name == "256") return CpuVectorBits::Bits256;
  if (name == "512") return CpuVectorBits::Bits512;
  return std::nullopt;
}

bool device_takes_512_bit_vectors(const DeviceInfo& device) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  // PoCL's CPU device compiles for the host's CPU, so the host's CPUID is the device's.
  const bool host_has_avx512 = __builtin_cpu_supports("avx512f");
#else
  const bool host_has_avx512 = false;
#endif
  // PoCL's device version names its LLVM target: "... HSTR: pthread-x86_64-pc-linux-gnu-<cpu>".
  return device.is_pocl_cpu() &&
         device.device_version.find("x86_64") != std::string::npos && host_has_avx512;
}

// The 16 lanes of 512-bit float vectors. More (32) measured the same on AMD EPYC Zen 5.
constexpr uint32_t kLanesAt512Bits = 16;

uint32_t cpu_vector_lanes_for(CpuVectorBits bits, const DeviceInfo& device) {
  if (bits == CpuVectorBits::Bits256) return 0;
  const bool takes_512 = device_takes_512_bit_vectors(device);
  std::string why_not;
  const bool reachable = takes_512 && pocl_vectoriser_reachable(&why_not);
  if (bits == CpuVectorBits::Auto) return reachable ? kLanesAt512Bits : 0;
  if (!takes_512)
    throw Error(ExitCode::Usage, "--cpu-vector-bits 512: " + device.label() +
                                      " is not PoCL's CPU device on an x86-64 CPU with AVX-512 (use 256 or auto)");
  if (!reachable)
    throw Error(ExitCode::Usage, "--cpu-vector-bits 512: the width of " + device.label() +
                                      "'s vectoriser cannot be set: " + why_not + " (use 256 or auto)");
  return kLanesAt512Bits;
}

std::string pocl_llvm_cpu(const DeviceInfo& device) {
  if (!device.is_pocl_cpu()) return "";
  const std::string marker = "-linux-gnu-";
  const size_t at = device.device_version.find(marker);
  if (at == std::string::npos) return "";
  const size_t begin = at + marker.size();
  const size_t end = device.device_version.find_first_of(" ,", begin);
  return device.device_version.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

bool device_lacks_fast_gathers(const DeviceInfo& device) {
  const std::string cpu = pocl_llvm_cpu(device);
  if (cpu.empty() || device.device_version.find("x86_64") == std::string::npos) return false;
  // LLVM 15's CPUs with the fast-gather tuning (X86.td: Skylake client and every later Intel
  // core, and the AVX-512 ones).
  static const char* const kFastGather[] = {"skylake", "cascadelake", "cooperlake", "cannonlake", "icelake",
                                            "tigerlake", "rocketlake", "sapphirerapids", "alderlake",
                                            "raptorlake", "meteorlake", "knl", "knm"};
  for (const char* prefix : kFastGather)
    if (cpu.rfind(prefix, 0) == 0) return false;
  return true;
}

const char* sphere_reads_name(SphereReads reads) {
  switch (reads) {
    case SphereReads::Indexed: return "indexed";
    case SphereReads::Selects: return "selects";
    default: return "auto";
  }
}

std::optional<SphereReads> parse_sphere_reads(const std::string& name) {
  if (name == "auto") return SphereReads::Auto;
  if (name == "indexed") return SphereReads::Indexed;
  if (name == "selects") return SphereReads::Selects;
  return std::nullopt;
}

bool sphere_reads_by_select_for(SphereReads reads, const DeviceInfo& device, Precision precision) {
  if (reads == SphereReads::Auto) return precision != Precision::Fast && device_lacks_fast_gathers(device);
  return reads == SphereReads::Selects;
}

const char* scene_loops_name(SceneLoops loops) {
  switch (loops) {
    case SceneLoops::Unrolled: return "unrolled";
    case SceneLoops::Rolled: return "rolled";
    default: return "auto";
  }
}

std::optional<SceneLoops> parse_scene_loops(const std::string& name) {
  if (name == "auto") return SceneLoops::Auto;
  if (name == "unrolled") return SceneLoops::Unrolled;
  if (name == "rolled") return SceneLoops::Rolled;
  return std::nullopt;
}

// CPUs unroll: PoCL vectorises only straight-line code across work-items, and the shading and
// intersection stages of both forms are written to be that. GPUs run each work-item in a SIMD
// lane anyway and gain nothing from straight-line code; unrolled, clang -O3 for gfx906 schedules
// the eight intersections of the book's scenes side by side (diffuse, nee: wf_shade 86 VGPRs,
// 2 waves per SIMD; rolled 64, 4 waves; wf_intersect 41 -> 21, 5 -> 10 waves; measured with
// scripts/gpu_compile.sh, docs/gpu-compilers.md). No GPU has timed either yet.
bool scene_loops_unrolled_for(SceneLoops loops, const DeviceInfo& device) {
  if (loops == SceneLoops::Auto) return device.is_cpu;
  return loops == SceneLoops::Unrolled;
}

KernelFeatures features_for_scene(const Scene& scene, Precision precision) {
  KernelFeatures f;
  f.precision = precision;
  f.estimator = parse_estimator(scene.settings.estimator).value_or(Estimator::Book);
  f.sampler = scene.settings.sampler;
  f.russian_roulette = scene.settings.rr_from >= 0;
  if (f.estimator == Estimator::Nee)
    f.light_count = static_cast<int>(light_caps(scene).size());
  // Only nee samples lights; a scene without emitting triangles keeps the kernel it had before
  // triangle lights existed (uniform pick over its spheres' caps, no triangle sampling compiled).
  f.triangle_lights = f.estimator == Estimator::Nee && has_triangle_lights(scene);
  f.phong = false;
  f.glass = false;
  f.mirror = false;
  f.pbr = false;
  f.pbr_transmission = false;
  f.pbr_volume = false;
  f.point_lights = f.spot_lights = f.directional_lights = false;
  for (const PunctualLight& l : scene.lights) {
    f.point_lights |= l.type == LightType::Point;
    f.spot_lights |= l.type == LightType::Spot;
    f.directional_lights |= l.type == LightType::Directional;
  }
  f.orthographic = scene.camera.projection == Projection::Orthographic;
  f.environment = !scene.environment              ? EnvironmentFeature::None
                  : !scene.environment->is_image() ? EnvironmentFeature::Constant
                                                    : EnvironmentFeature::Image;
  const TextureUse textures = texture_use(scene);
  // A material cut by its alpha needs the texturing buffer's records (kernels/alpha.cl) even
  // without an image: the texture code comes with it (with no texel storage compiled).
  f.textures = textures.any || textures.alpha || textures.vertex_colors;
  f.alpha = textures.alpha;
  f.vertex_colors = textures.vertex_colors;
  f.texel_storages = textures.storages;
  f.slot_storages = textures.slot_storages;
  f.texel_channels = textures.channel_counts;
  f.texture_wraps = textures.wraps;
  f.normal_maps = textures.normal_maps;
  f.emission_textures = textures.emission;
  f.sphere_textures = textures.spheres;
  f.spheres_in_bvh = spheres_in_hierarchy(scene);
  const std::vector<bool> in_loop = loop_spheres(scene);
  f.sphere_count = static_cast<int>(std::count(in_loop.begin(), in_loop.end(), true));
  f.triangles = false;
  const auto uses = [&f](const Material& m) {
    f.phong |= m.type == MaterialType::Phong;
    f.glass |= m.type == MaterialType::Glass;
    f.mirror |= m.type == MaterialType::Mirror;
    f.pbr |= m.type == MaterialType::Pbr;
    f.pbr_transmission |= m.type == MaterialType::Pbr && m.transmission > 0;
    f.pbr_volume |= m.type == MaterialType::Pbr && m.transmission > 0 && m.thickness > 0;
  };
  for (const Sphere& s : scene.spheres) uses(s.material);
  for (const TriangleMesh& m : scene.meshes) {
    uses(m.material);
    f.triangles |= !m.triangles.empty();
  }
  const TriangleLoopChoice loop = triangle_loop_choice(scene);
  f.loop_triangles = loop.triangles;
  f.hierarchy_triangles = loop.hierarchy_triangles;
  return f;
}

void require_estimator_sees_lights(const Scene& scene) {
  if (scene.lights.empty() || parse_estimator(scene.settings.estimator) != Estimator::Book) return;
  const PunctualLight& l = scene.lights.front();
  throw Error(ExitCode::Usage,
              (l.where.file.empty() ? scene.file : l.where.str()) + ": " + l.name + ": a " + light_type_name(l.type) +
                  " light is a delta light, which only next-event estimation reaches: the book estimator would "
                  "render the scene without it (use --estimator nee, or render.estimator = \"nee\")");
}

KernelFeatures generic_features(Precision precision) {
  KernelFeatures f;
  f.precision = precision;
  f.generic = true;
  return f;
}

bool reads_spheres_by_select(const KernelFeatures& features) {
  return features.no_fast_gather && !features.generic && !features.spheres_in_bvh;
}

bool hit_carries_sphere_centre(const KernelFeatures& features) {
  const Intersection intersection = features.intersection.value_or(default_intersection(features.precision));
  return features.lockstep_group > 0 && features.unroll_scene_loops && !features.has_hierarchy() &&
         !features.triangles && !reads_spheres_by_select(features) && intersection != Intersection::Centre;
}

bool picks_material_by_select(const KernelFeatures& features) {
  return reads_spheres_by_select(features) || hit_carries_sphere_centre(features);
}

bool scatter_draws_paired(const KernelFeatures& features) {
  return !features.glass && !features.pbr && !features.russian_roulette;
}

bool lockstep_pairs_segments(const KernelFeatures& features) {
  return !features.generic && features.lockstep_group > 0 && scatter_draws_paired(features) &&
         features.unroll_scene_loops && !features.has_hierarchy() && !features.triangles_in_loop();
}

// Each slot's storages (texture.cl): its own mask where it has images; where it has none its lookup
// never runs, and the float storage alone (a typed read, no sRGB) is the least code to compile.
// "base colour 8-bit, metallic-roughness half, ...": the slots with images, each its storages.
static std::string slot_names(const KernelFeatures& features) {
  const char* slots[kTextureSlots] = {"base colour", "metallic-roughness", "normal map", "emission"};
  const char* storages[3] = {"8-bit", "half", "float"};
  std::string out;
  for (int i = 0; i < kTextureSlots; ++i) {
    const uint32_t mask = features.slot_storages[size_t(i)] & features.texel_storages;
    if (mask == 0) continue;
    std::string these;
    for (int b = 0; b < 3; ++b)
      if (mask & (1u << b)) these += (these.empty() ? "" : "+") + std::string(storages[b]);
    out += (out.empty() ? "" : ", ") + std::string(slots[i]) + " " + these;
  }
  return out.empty() ? "no slot" : out;
}

static std::string slot_storage_options(const KernelFeatures& features) {
  const char* names[kTextureSlots] = {"BASE", "MR", "NORMAL", "EMISSION"};
  std::string out;
  for (int i = 0; i < kTextureSlots; ++i) {
    const uint32_t mask = features.slot_storages[size_t(i)] & features.texel_storages;
    out += std::string(" -DCLPT_") + names[i] + "_STORAGES=" + std::to_string(mask != 0 ? mask : 4u);
  }
  return out;
}

std::string kernel_build_options(const KernelFeatures& features) {
  std::ostringstream o;
  // OpenCL C 1.2: what PoCL compiles and every GPU driver accepts.
  o << "-cl-std=CL1.2";
  // Fast maths lets the compiler reassociate, contract and drop signed zeros. Not
  // -cl-fast-relaxed-math: its -cl-finite-math-only stops PoCL's work-item loop vectoriser (LLVM
  // 15: "instruction return type cannot be vectorized"), which made the fast lockstep megakernel
  // 4x slower than robust (docs/performance.md, "Presets"). The film's NaN/Inf guard is a bit test
  // (maths.cl) either way.
  if (features.precision == Precision::Fast) o << " -cl-unsafe-math-optimizations";
  o << " -DCLPT_PRECISION=" << static_cast<int>(features.precision);
  o << " -DCLPT_INTERSECT=" << static_cast<int>(features.intersection.value_or(default_intersection(features.precision)));
  o << " -DCLPT_HAS_PHONG=" << (features.phong ? 1 : 0);
  o << " -DCLPT_HAS_GLASS=" << (features.glass ? 1 : 0);
  o << " -DCLPT_HAS_MIRROR=" << (features.mirror ? 1 : 0);
  // Named only when on (KernelFeatures: absent is off in a specialised kernel, on in the generic).
  if (!features.generic) {
    if (features.pbr) o << " -DCLPT_HAS_PBR=1";
    if (features.pbr) o << " -DCLPT_HAS_PBR_TRANSMISSION=" << (features.pbr_transmission ? 1 : 0);
    if (features.pbr) o << " -DCLPT_HAS_PBR_VOLUME=" << (features.pbr_volume ? 1 : 0);
    if (features.point_lights) o << " -DCLPT_HAS_POINT_LIGHTS=1";
    if (features.spot_lights) o << " -DCLPT_HAS_SPOT_LIGHTS=1";
    if (features.directional_lights) o << " -DCLPT_HAS_DIRECTIONAL_LIGHTS=1";
    if (features.orthographic) o << " -DCLPT_HAS_ORTHOGRAPHIC=1";
    if (features.environment != EnvironmentFeature::None)
      o << " -DCLPT_HAS_ENVIRONMENT=" << static_cast<int>(features.environment);
    if (features.textures)
      o << " -DCLPT_HAS_TEXTURES=1 -DCLPT_TEXEL_STORAGES=" << features.texel_storages
        << " -DCLPT_TEXEL_CHANNELS=" << features.texel_channels << " -DCLPT_TEXTURE_WRAPS=" << features.texture_wraps
        << " -DCLPT_HAS_NORMAL_MAPS=" << (features.normal_maps ? 1 : 0)
        << " -DCLPT_HAS_EMISSION_TEXTURES=" << (features.emission_textures ? 1 : 0)
        << slot_storage_options(features);
    if (features.textures && features.sphere_textures) o << " -DCLPT_HAS_SPHERE_TEXTURES=1";
    if (features.alpha) o << " -DCLPT_HAS_ALPHA=1";
    if (features.vertex_colors) o << " -DCLPT_HAS_VERTEX_COLORS=1";
  }
  o << " -DCLPT_HAS_TRIANGLES=" << (features.generic || features.triangles ? 1 : 0);
  o << " -DCLPT_HAS_BVH=" << (features.has_hierarchy() ? 1 : 0);
  o << " -DCLPT_HAS_TRIANGLE_LIGHTS=" << (features.generic || features.triangle_lights ? 1 : 0);
  o << " -DCLPT_HAS_RR=" << (features.generic || features.russian_roulette ? 1 : 0);
  if (!features.generic) o << " -DCLPT_ESTIMATOR=" << static_cast<int>(features.estimator);
  if (!features.generic) o << " -DCLPT_SAMPLER=" << static_cast<int>(features.sampler);
  // A specialised kernel fixes its sphere loop, at 0 when the spheres are in the hierarchy or
  // there are none (then no sphere loop is compiled at all).
  if (!features.generic) o << " -DCLPT_SPHERE_COUNT=" << features.sphere_count;
  // Named only when on: the kernels of scenes without a small mesh keep their options.
  if (features.triangles_in_loop()) o << " -DCLPT_TRIANGLE_COUNT=" << features.loop_triangles;
  if (features.loop_beside_hierarchy()) o << " -DCLPT_BVH_ROOT=1";
  if (!features.generic && features.light_count >= 0) o << " -DCLPT_LIGHT_COUNT=" << features.light_count;
  if (features.lockstep_group > 0) o << " -DCLPT_LOCKSTEP_GROUP=" << features.lockstep_group;
  // Only where there is a specialised loop to keep rolled: the generic kernel's programs stay one.
  const bool specialised_loops = !features.generic;
  if (specialised_loops && !features.unroll_scene_loops) o << " -DCLPT_UNROLL_SCENE_LOOPS=0";
  // A leaf's four triangles in one vector test only on PoCL's CPU device with its vectoriser's width
  // set, in a float preset (bvh.cl, wide_leaf_test): named only elsewhere, where they are tested one
  // at a time.
  if (features.has_hierarchy() && !features.wide_leaf_test()) o << " -DCLPT_WIDE_LEAF_TEST=0";
  // Read by no kernel: PoCL's vectoriser takes the width from the host (cl/pocl_vectoriser.h), and
  // it is here so that PoCL's cache and clpt's keep a 16-lane build apart from LLVM's own.
  if (features.cpu_vector_lanes > 0) o << " -DCLPT_CPU_VECTOR_LANES=" << features.cpu_vector_lanes;
  if (reads_spheres_by_select(features)) o << " -DCLPT_NO_FAST_GATHER=1";
  if (hit_carries_sphere_centre(features)) o << " -DCLPT_HIT_CENTRE=1";
  if (picks_material_by_select(features) && !reads_spheres_by_select(features)) o << " -DCLPT_MATERIAL_BY_SELECT=1";
  if (!features.generic) o << " -DCLPT_SCATTER_DRAW_PAIRS=" << (scatter_draws_paired(features) ? 1 : 0);
  // Named only when off where the lockstep loop would pair segments: other kernels keep their options.
  if (features.lockstep_group > 0 && scatter_draws_paired(features) && features.unroll_scene_loops &&
      !features.has_hierarchy() && !lockstep_pairs_segments(features))
    o << " -DCLPT_LOCKSTEP_SEGMENT_PAIRS=0";
  if (features.aovs) o << " -DCLPT_AOVS=1";
  if (features.build_nonce) o << " -DCLPT_BUILD_NONCE=" << features.build_nonce;
  return o.str();
}

std::string explain_kernel_options(const KernelFeatures& features) {
  std::ostringstream o;
  o << "kernel specialisation:\n";
  o << "  precision: " << precision_name(features.precision)
    << (features.precision == Precision::Fast     ? " (float, -cl-unsafe-math-optimizations, native maths)"
        : features.precision == Precision::Double ? " (fp64 arithmetic, cl_khr_fp64)"
                                                  : " (float, IEEE maths, the accurate intersection)")
    << "\n";
  o << "  intersection: " << intersection_name(features.intersection.value_or(default_intersection(features.precision)))
    << (features.intersection ? " (--intersection)" : " (the preset's)") << "\n";
  o << "  estimator: "
    << (features.generic ? std::string("chosen at run time (generic kernel)")
                         : std::string(estimator_name(features.estimator)) +
                               (features.estimator == Estimator::Nee ? " (next-event estimation + MIS compiled in)"
                                                                     : " (no light sampling compiled)"))
    << "\n";
  o << "  sampler: "
    << (features.generic ? std::string("chosen at run time (generic kernel)")
                         : std::string(sampler_name(features.sampler)) +
                               (features.sampler == Sampler::Grid ? " (fixed sub-pixel positions: no camera draw compiled)"
                                : features.sampler == Sampler::Sobol ? " (Sobol points compiled)"
                                : features.sampler == Sampler::SobolGrid ? " (Sobol points compiled; camera samples at the grid's 16 positions)"
                                                                     : " (Philox draws only; no Sobol points compiled)"))
    << "\n";
  o << "  Russian roulette: "
    << (features.generic ? "compiled, enabled at run time"
                         : features.russian_roulette ? "compiled (--rr-from)" : "left out (no --rr-from)")
    << "\n";
  o << "  Lambertian and emitter shading: always compiled\n";
  o << "  Phong shading: " << (features.phong ? "compiled (the scene has a Phong material)"
                                              : "left out (no Phong material in the scene)")
    << "\n";
  o << "  glass shading: " << (features.glass ? "compiled (the scene has a glass material)"
                                              : "left out (no glass material in the scene)")
    << "\n";
  o << "  mirror shading: " << (features.mirror ? "compiled (the scene has a mirror material)"
                                                : "left out (no mirror material in the scene)")
    << "\n";
  o << "  Pbr shading: "
    << (features.generic ? "compiled (generic kernel)"
        : features.pbr   ? "compiled (the scene has a pbr material: GGX with visible-normal sampling, bsdf_pbr.cl)"
                         : "left out (no pbr material in the scene)")
    << "\n";
  o << "  Pbr transmission: "
    << (features.generic ? "compiled (generic kernel)"
        : features.pbr_transmission ? "compiled (a pbr material has transmission > 0: the thin-walled lobe)"
                                    : "left out (no pbr material with transmission)")
    << "\n";
  o << "  Pbr volume: "
    << (features.generic ? "compiled (generic kernel)"
        : features.pbr_volume ? "compiled (a transmitting pbr material has a thickness: rough refraction, Beer's law)"
                              : "left out (no transmitting pbr material with a thickness)")
    << "\n";
  const auto light_line = [&](const char* kind, bool on) {
    o << "  " << kind << " lights: "
      << (features.generic ? std::string("compiled (generic kernel)")
          : on ? std::string("compiled (the scene has one: next-event estimation only, picked by power)")
               : std::string("left out (none in the scene)"))
      << "\n";
  };
  light_line("point", features.point_lights);
  light_line("spot", features.spot_lights);
  light_line("directional", features.directional_lights);
  o << "  environment: "
    << (features.generic ? "an image, sampled by nee (generic kernel; a scene without one reads a black texel)"
        : features.environment == EnvironmentFeature::Image
            ? "an image (seen by escaping rays; nee samples it by luminance x sin(theta), MIS with BSDF sampling)"
        : features.environment == EnvironmentFeature::Constant
            ? "a constant colour (seen by escaping rays; not light-sampled: BSDF sampling is already ideal for it)"
            : "left out (none in the scene: escaping rays are black)")
    << "\n";
  {
    const auto names = [](uint32_t mask, std::initializer_list<const char*> words) {
      std::string out;
      uint32_t bit = 0;
      for (const char* w : words) {
        if (mask & (1u << bit)) out += (out.empty() ? "" : ", ") + std::string(w);
        ++bit;
      }
      return out;
    };
    o << "  textures: "
      << (features.generic ? std::string("compiled (generic kernel: every storage, channel count and wrap mode)")
          : features.textures && features.texel_storages == 0
              ? std::string(features.vertex_colors ? "compiled for the vertex colours and alpha records alone (no image: no texel storage)"
                                                   : "compiled for the alpha records alone (no image: no texel storage)")
          : features.textures
              ? "compiled (a textured material on a " +
                    std::string(features.sphere_textures ? "mesh or sphere; spheres by the spherical mapping: " : "mesh: ") +
                    names(features.texel_storages, {"8-bit", "half", "float"}) + " texels (" +
                    slot_names(features) + "); " + names(features.texel_channels, {"1", "2", "3", "4"}) + " channel(s); " +
                    names(features.texture_wraps, {"repeat", "clamp", "mirror"}) + " wrap; normal maps " +
                    (features.normal_maps ? "compiled" : "left out") + "; emission textures " +
                    (features.emission_textures ? "compiled" : "left out") + ")"
              : std::string("left out (no textured material)"))
      << "\n";
    o << "  alpha: "
      << (features.generic ? "compiled (generic kernel: MASK and BLEND surfaces cut out in every ray query)"
          : features.alpha ? "compiled (a MASK or BLEND material: its surface cut out in every ray query, shadow rays too)"
                           : "left out (no MASK or BLEND material)")
      << "\n";
    o << "  vertex colours: "
      << (features.generic ? "compiled (generic kernel: glTF COLOR_0 read where a scene has it)"
          : features.vertex_colors ? "compiled (a glTF mesh with COLOR_0: its colours multiply the base colour and alpha)"
                                   : "left out (no glTF COLOR_0)")
      << "\n";
  }
  o << "  camera: "
    << (features.generic ? "perspective or orthographic at run time (generic kernel)"
        : features.orthographic ? "orthographic compiled (the scene's camera is orthographic)"
                                : "perspective only (the pinhole)")
    << "\n";
  o << "  sphere loop: "
    << (features.generic ? std::string("run-time sphere count (generic kernel)")
        : features.spheres_in_bvh
            ? "fixed at the scene's " + std::to_string(features.sphere_count) +
                  " large spheres; the others are hierarchy primitives (more than " +
                  std::to_string(kMaxLoopSpheres) + " spheres, the measured crossover)"
        : "fixed at the scene's " + std::to_string(features.sphere_count) + " spheres (at most " +
              std::to_string(kMaxLoopSpheres) + ": a loop beats traversal)")
    << "\n";
  o << "  triangles: "
    << (features.generic ? "compiled (generic kernel)"
        : features.triangles ? "compiled (the scene has meshes)" : "left out (no mesh in the scene)")
    << "\n";
  o << "  triangle loop: "
    << (features.generic ? std::string("left out (generic kernel: the hierarchy)")
        : !features.triangles ? std::string("left out (no mesh in the scene)")
        : features.loop_beside_hierarchy()
            ? "fixed at the " + std::to_string(features.loop_triangles) +
                  " triangles of the scene's meshes of large triangles, unrolled (walls, floors: 100x the median "
                  "triangle's area, at most " + std::to_string(kMaxLoopTriangles) + "); the others in the hierarchy"
        : features.triangles_in_loop()
            ? "fixed at the scene's " + std::to_string(features.loop_triangles) + " triangles, unrolled (at most " +
                  std::to_string(kMaxLoopTriangles) + "; measured 3x the hierarchy on the Cornell box's 32)"
        : features.spheres_in_bvh ? std::string("left out (the spheres are in the hierarchy)")
        : features.loop_triangles > 0 && features.hierarchy_triangles && features.unroll_scene_loops &&
                  features.cpu_vector_lanes > 0
            ? "left out (the " + std::to_string(features.loop_triangles) +
                  " triangles of the scene's meshes of large triangles go to the loop in the lockstep megakernel only: "
                  "here the hierarchy holds them)"
        : features.loop_triangles == 0
            ? "left out (more than " + std::to_string(kMaxLoopTriangles) +
                  " triangles and no mesh of large ones: the hierarchy)"
            : std::string("left out (rolled scene loops, or not PoCL's CPU device with its 16 lanes set: the hierarchy)"))
    << "\n";
  o << "  hierarchy traversal: "
    << (features.generic ? "compiled (generic kernel; used when the scene has a hierarchy)"
        : features.has_hierarchy()
            ? std::string("compiled (") +
                  (features.triangles && features.spheres_in_bvh ? "triangles and spheres"
                   : features.triangles                          ? "triangles"
                                                                 : "spheres") +
                  " in the hierarchy; closest hit and any-hit shadow rays" +
                  (features.triangles ? (features.wide_leaf_test() ? "; a leaf's four triangles in one vector test"
                                                                  : "; a leaf's triangles one at a time (the double preset, or not PoCL's CPU device with its 16 lanes set)")
                                      : "") +
                  ")"
            : std::string(features.triangles ? "left out (the triangles are in the unrolled loop, and few enough spheres for theirs)"
                                             : "left out (no triangles, and few enough spheres for the loop)"))
    << "\n";
  o << "  triangle lights: "
    << (features.generic ? "compiled (generic kernel; the pick is uniform unless the scene has emitting triangles)"
        : features.triangle_lights
            ? "compiled (nee and an emitting mesh: its triangles are sampled by area, lights picked by power "
              "from an alias table)"
        : features.estimator != Estimator::Nee ? "left out (the book estimator samples no lights)"
                                                : "left out (no emitting mesh: spheres' caps only, picked uniformly)")
    << "\n";
  if (!features.generic && features.estimator == Estimator::Nee)
    o << "  light loop: "
      << (features.light_count >= 0 ? "fixed at the scene's " + std::to_string(features.light_count) +
                                          " sampled sphere light(s)"
                                    : std::string("run-time light count"))
      << "\n";
  if (!features.generic)
    o << "  scene loops: " << (features.unroll_scene_loops ? "unrolled" : "rolled") << " (--scene-loops "
      << scene_loops_name(features.scene_loops)
      << (features.scene_loops == SceneLoops::Auto ? ": unrolled on CPUs, rolled on GPUs" : "") << ")\n";
  const char* auto_rule =
      features.cpu_vector_bits == CpuVectorBits::Auto ? ": 512 bits on PoCL's CPU device with AVX-512" : "";
  o << "  CPU vector width: "
    << (features.cpu_vector_lanes == 0
            ? std::string("the compiler's choice (--cpu-vector-bits ") + cpu_vector_bits_name(features.cpu_vector_bits) +
                  auto_rule + ")"
            : "512 bits, " + std::to_string(features.cpu_vector_lanes) +
                  " work-items per vector iteration, set on PoCL's vectoriser (--cpu-vector-bits " +
                  cpu_vector_bits_name(features.cpu_vector_bits) + auto_rule + ")")
    << "\n";
  o << "  hit sphere reads: "
    << (!features.no_fast_gather ? std::string("indexed")
        : reads_spheres_by_select(features)
            ? std::string("selects over the loop's spheres, the lockstep state in local memory")
            : std::string("indexed (selects asked for, but the kernel is generic or its spheres are in the hierarchy)"))
    << " (--sphere-reads " << sphere_reads_name(features.sphere_reads)
    << (features.sphere_reads == SphereReads::Auto
            ? ": selects where the device's compiler has no fast gathers, but with the fast preset"
            : "")
    << ")\n";
  o << "  hit sphere's centre: "
    << (hit_carries_sphere_centre(features)
            ? "carried through the sphere loop (the lockstep megakernel, every sphere in the unrolled loop)"
            : "read from the hit sphere (per-path or wavefront kernel, a rolled loop, a hierarchy, selects or the textbook intersection)")
    << "\n";
  o << "  hit sphere's material: " << (picks_material_by_select(features) ? "selects over the loop's spheres" : "indexed")
    << "\n";
  o << "  scattering draws: "
    << (features.generic ? std::string("as the scene's parameters say (one per bounce, or one per two without glass, pbr and Russian roulette)")
        : scatter_draws_paired(features)
            ? std::string("one per two bounces (no glass, no Russian roulette)") +
                  (lockstep_pairs_segments(features) ? ", evaluated once for the lockstep loop's two segments"
                   : features.lockstep_group > 0 && !features.has_hierarchy() && features.unroll_scene_loops
                       ? ", the lockstep loop one segment a step (the triangle loop: its cold compile halved)"
                       : "")
            : std::string("one per bounce (glass, a pbr material or Russian roulette read a third or fourth uniform)"))
    << "\n";
  if (features.aovs)
    o << "  first-hit layers: compiled (--aovs: albedo, normal and depth recorded per path and summed per "
         "pixel; kernels/aov.cl)\n";
  o << "  build options: " << kernel_build_options(features) << "\n";
  return o.str();
}

}  // namespace clpt
