// The covering set of kernel variants (host/tools/kernel_variants.h): every value and every pair
// of values is in some variant, the set is the same on every run, and each variant builds what a
// render of its scene would; and the per-device choice of the CPU vector width.
#include <gtest/gtest.h>

#include <set>

#include "cl/pocl_vectoriser.h"
#include "render_test_util.h"
#include "render/render_plan.h"
#include "scene/device_scene.h"
#include "tools/kernel_variants.h"
#include "util/error.h"

namespace clpt::test {
namespace {

TEST(KernelVariants, CoverEveryPairOfValues) {
  const std::vector<KernelVariant> variants = covering_kernel_variants();
  EXPECT_TRUE(uncovered_pairs(variants).empty());
  // The check itself can fail: without any one variant some pair goes uncovered (the greedy set
  // has no redundant member).
  for (size_t i = 0; i < variants.size(); ++i) {
    std::vector<KernelVariant> fewer = variants;
    fewer.erase(fewer.begin() + long(i));
    EXPECT_FALSE(uncovered_pairs(fewer).empty()) << "variant " << variants[i].name() << " adds no pair";
  }
  // 4 x 4 values of the two largest dimensions need at least 16 variants (of which the book
  // estimator goes with only one).
  EXPECT_GE(variants.size(), 13u);
  // The greedy cover stays within 1.5x of that bound (20 with 15 dimensions, the textures' third
  // value, textured spheres, included; 22 before it: the greedy pick is no optimum).
  EXPECT_LE(variants.size(), 24u);
  std::set<std::string> names;
  for (const KernelVariant& v : variants) EXPECT_TRUE(names.insert(v.name()).second) << v.name();
}

// The Oclgrind tier's default part (docs/oclgrind.md): the shortest prefix holding every value of
// every dimension, and no shorter one does.
TEST(KernelVariants, ValueCoveringPrefixHoldsEveryValue) {
  const auto variants = covering_kernel_variants();
  const size_t k = value_covering_prefix(variants);
  ASSERT_GE(k, 1u);
  ASSERT_LT(k, variants.size());  // the pairs need more variants than the values
  const auto& dims = kernel_variant_dimensions();
  auto values_held = [&](size_t prefix) {
    size_t held = 0;
    for (size_t d = 0; d < dims.size(); ++d) {
      std::set<int> seen;
      for (size_t i = 0; i < prefix; ++i) seen.insert(variants[i].choice[d]);
      held += seen.size();
    }
    return held;
  };
  size_t all = 0;
  for (const auto& d : dims) all += d.values.size();
  EXPECT_EQ(values_held(k), all);
  EXPECT_LT(values_held(k - 1), all);
}

TEST(KernelVariants, SameListEveryTime) {
  const auto a = covering_kernel_variants(), b = covering_kernel_variants();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].name(), b[i].name());
}

TEST(KernelVariants, ScenesAndProgramsFollowTheVariant) {
  const Scene diffuse = load_book_scene("diffuse");
  for (const KernelVariant& v : covering_kernel_variants()) {
    const Scene scene = variant_scene(diffuse, v);
    const VariantProgram p = variant_program(scene, v);
    EXPECT_EQ(p.entry_file, v.form() == ExecutionForm::Wavefront ? "wavefront.cl" : "megakernel.cl");
    EXPECT_EQ(p.features.precision, v.precision());
    EXPECT_EQ(p.features.generic, v.generic());
    if (!v.generic()) {
      EXPECT_EQ(p.features.phong, v.has_phong()) << v.name();
      EXPECT_EQ(p.features.glass, v.has_glass()) << v.name();
      EXPECT_EQ(p.features.estimator, v.estimator()) << v.name();
      EXPECT_EQ(p.features.russian_roulette, v.russian_roulette()) << v.name();
      EXPECT_EQ(p.features.triangles, v.has_mesh()) << v.name();
      EXPECT_EQ(p.features.spheres_in_bvh, v.has_mesh()) << v.name();
      EXPECT_EQ(p.features.has_hierarchy(), v.has_mesh()) << v.name();
      EXPECT_EQ(p.features.pbr, v.has_pbr()) << v.name();
      EXPECT_EQ(p.features.pbr_transmission, v.has_pbr_transmission()) << v.name();
      EXPECT_EQ(p.features.pbr_volume, v.has_pbr_volume()) << v.name();
      EXPECT_EQ(p.features.point_lights, v.punctual_light() == 1) << v.name();
      EXPECT_EQ(p.features.spot_lights, v.punctual_light() == 2) << v.name();
      EXPECT_EQ(p.features.directional_lights, v.punctual_light() == 3) << v.name();
      EXPECT_EQ(p.features.orthographic, v.orthographic()) << v.name();
      EXPECT_EQ(p.features.textures, v.textures() != 0) << v.name();
      EXPECT_EQ(p.features.vertex_colors, v.textures() == 2) << v.name();
      EXPECT_EQ(p.features.texel_storages, v.textures() != 0 ? (v.has_pbr() ? 7u : v.textures() == 3 ? 5u : 3u) : 0u)
          << v.name();
      EXPECT_EQ(p.features.sphere_textures, v.textures() == 3) << v.name();
      EXPECT_EQ(kernel_build_options(p.features).find("-DCLPT_HAS_SPHERE_TEXTURES=1") != std::string::npos,
                v.textures() == 3)
          << v.name();
    }
    EXPECT_EQ(p.features.aovs, v.aovs()) << v.name();  // generic or not: the render's request
    EXPECT_EQ(p.features.lockstep_group > 0,
              v.form() == ExecutionForm::Megakernel && v.megakernel_loop() == MegakernelLoop::Lockstep);
    EXPECT_EQ(scene.settings.rr_from >= 0, v.russian_roulette());
    // A specialised rolled variant builds with its loops rolled; every other keeps the option out.
    const bool rolled = !v.generic() && v.scene_loops() == SceneLoops::Rolled;
    EXPECT_EQ(kernel_build_options(p.features).find("-DCLPT_UNROLL_SCENE_LOOPS=0") != std::string::npos, rolled)
        << v.name();
  }
}

// --cpu-vector-bits: 256 leaves the width to LLVM's cost model; 512, and auto where 512 can be
// had, set PoCL's vectoriser to 16 lanes (cl/pocl_vectoriser.h): only PoCL on an x86 CPU with
// AVX-512. Elsewhere auto stays with the compiler and 512 is refused.
TEST(KernelOptions, CpuVectorBits512IsRefusedWhereTheDeviceCannotTakeIt) {
  DeviceInfo gpu;
  gpu.name = "some GPU";
  gpu.platform_name = "NVIDIA CUDA";
  gpu.is_gpu = true;
  DeviceInfo simulator = gpu;
  simulator.platform_name = "Oclgrind";
  simulator.is_gpu = false;
  simulator.is_cpu = true;
  simulator.device_version = "OpenCL 1.2 Oclgrind";
  for (const DeviceInfo& d : {gpu, simulator}) {
    SCOPED_TRACE(d.platform_name);
    EXPECT_FALSE(device_takes_512_bit_vectors(d));
    EXPECT_EQ(cpu_vector_lanes_for(CpuVectorBits::Auto, d), 0u);
    EXPECT_EQ(cpu_vector_lanes_for(CpuVectorBits::Bits256, d), 0u);
    try {
      cpu_vector_lanes_for(CpuVectorBits::Bits512, d);
      ADD_FAILURE() << "512 bits accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::Usage);
      EXPECT_NE(std::string(e.what()).find("--cpu-vector-bits 512"), std::string::npos) << e.what();
    }
  }
}

TEST(KernelOptions, CpuVectorBits512SetsSixteenLanesOnPoclAvx512) {
  list_devices();  // loads PoCL, whose LLVM the lanes are set on
  DeviceInfo pocl;
  pocl.name = "pthread-skylake-avx512";
  pocl.platform_name = "Portable Computing Language";
  pocl.is_cpu = true;
  pocl.device_version = "OpenCL 3.0 PoCL HSTR: pthread-x86_64-pc-linux-gnu-skylake-avx512";
  KernelFeatures f = features_for_scene(load_book_scene("diffuse"));
  EXPECT_EQ(kernel_build_options(f).find("CLPT_CPU_VECTOR_LANES"), std::string::npos);
  EXPECT_NE(explain_kernel_options(f).find("CPU vector width: the compiler's choice"), std::string::npos);
  if (!device_takes_512_bit_vectors(pocl)) GTEST_SKIP() << "this host's CPU has no AVX-512";
  std::string why_not;
  if (!pocl_vectoriser_reachable(&why_not)) GTEST_SKIP() << "PoCL's vectoriser is not reachable: " << why_not;
  EXPECT_EQ(cpu_vector_lanes_for(CpuVectorBits::Bits256, pocl), 0u);
  EXPECT_EQ(cpu_vector_lanes_for(CpuVectorBits::Auto, pocl), 16u);
  f.cpu_vector_lanes = cpu_vector_lanes_for(CpuVectorBits::Bits512, pocl);
  EXPECT_EQ(f.cpu_vector_lanes, 16u);
  EXPECT_NE(kernel_build_options(f).find(" -DCLPT_CPU_VECTOR_LANES=16"), std::string::npos);
  EXPECT_NE(explain_kernel_options(f).find("CPU vector width: 512 bits, 16 work-items per vector iteration"),
            std::string::npos);
}

// Setting the width needs PoCL's shared LLVM in the process; where it is missing the reason is
// given and asking for lanes is a logic error (the plan checks first), while 0 (LLVM's own choice,
// never set) stays a no-op so that every PoCL launch may ask for its kernel's width.
TEST(PoclVectoriser, SetsTheWidthOnlyWhereItIsReachable) {
  list_devices();
  std::string why_not;
  if (pocl_vectoriser_reachable(&why_not)) {
    EXPECT_NO_THROW(set_pocl_vectoriser_lanes(16));
    EXPECT_NO_THROW(set_pocl_vectoriser_lanes(16));
    EXPECT_NO_THROW(set_pocl_vectoriser_lanes(0));
  } else {
    EXPECT_FALSE(why_not.empty());
    EXPECT_NO_THROW(set_pocl_vectoriser_lanes(0));
    EXPECT_THROW(set_pocl_vectoriser_lanes(16), std::logic_error);
  }
}

// --sphere-reads auto: selects on PoCL CPUs whose LLVM CPU has no fast gathers, read from the
// device version; indexed on the others and on every non-PoCL device. Selects are compiled only
// into specialised kernels whose spheres are all in the loop.
TEST(KernelOptions, SphereReadsBySelectWhereTheCompilerHasNoFastGathers) {
  DeviceInfo pocl;
  pocl.name = "pthread-haswell-AMD EPYC";
  pocl.platform_name = "Portable Computing Language";
  pocl.is_cpu = true;
  const auto on = [&pocl](const std::string& llvm_cpu) {
    pocl.device_version = "OpenCL 3.0 PoCL HSTR: pthread-x86_64-pc-linux-gnu-" + llvm_cpu + ", driver 3.1";
    return pocl;
  };
  EXPECT_EQ(pocl_llvm_cpu(on("skylake-avx512")), "skylake-avx512");
  for (const char* slow : {"haswell", "broadwell", "znver2", "znver3", "x86-64"}) {
    SCOPED_TRACE(slow);
    EXPECT_TRUE(device_lacks_fast_gathers(on(slow)));
    EXPECT_TRUE(sphere_reads_by_select_for(SphereReads::Auto, on(slow), Precision::Robust));
    EXPECT_TRUE(sphere_reads_by_select_for(SphereReads::Auto, on(slow), Precision::Double));
    EXPECT_FALSE(sphere_reads_by_select_for(SphereReads::Auto, on(slow), Precision::Fast));
    EXPECT_FALSE(sphere_reads_by_select_for(SphereReads::Indexed, on(slow), Precision::Robust));
  }
  for (const char* fast : {"skylake", "skylake-avx512", "icelake-server", "sapphirerapids", "knl"}) {
    SCOPED_TRACE(fast);
    EXPECT_FALSE(device_lacks_fast_gathers(on(fast)));
    EXPECT_FALSE(sphere_reads_by_select_for(SphereReads::Auto, on(fast), Precision::Robust));
    EXPECT_TRUE(sphere_reads_by_select_for(SphereReads::Selects, on(fast), Precision::Fast));
  }
  DeviceInfo gpu;
  gpu.platform_name = "NVIDIA CUDA";
  gpu.is_gpu = true;
  gpu.device_version = "OpenCL 3.0 CUDA";
  EXPECT_EQ(pocl_llvm_cpu(gpu), "");
  EXPECT_FALSE(device_lacks_fast_gathers(gpu));
  EXPECT_EQ(parse_sphere_reads("selects"), SphereReads::Selects);
  EXPECT_FALSE(parse_sphere_reads("gathers").has_value());

  KernelFeatures f = features_for_scene(load_book_scene("diffuse"));
  f.no_fast_gather = true;
  EXPECT_NE(kernel_build_options(f).find(" -DCLPT_NO_FAST_GATHER=1"), std::string::npos);
  EXPECT_NE(explain_kernel_options(f).find("hit sphere reads: selects over the loop's spheres"), std::string::npos);
  KernelFeatures generic = generic_features();
  generic.no_fast_gather = true;
  EXPECT_EQ(kernel_build_options(generic).find("CLPT_NO_FAST_GATHER"), std::string::npos);
  f.spheres_in_bvh = true;
  EXPECT_EQ(kernel_build_options(f).find("CLPT_NO_FAST_GATHER"), std::string::npos);
}

// One draw serves two bounces exactly where scattering reads two uniforms (path.cl,
// scatter_draw): not with glass (u2) or Russian roulette (u3). The specialised kernel fixes the
// rule and the render's parameters carry the same one for the generic kernel.
TEST(KernelOptions, ScatterDrawsArePairedWithoutGlassAndRoulette) {
  const auto paired = [](const Scene& scene) {
    const bool fixed = scatter_draws_paired(features_for_scene(scene));
    const std::string options = kernel_build_options(features_for_scene(scene));
    EXPECT_NE(options.find(std::string(" -DCLPT_SCATTER_DRAW_PAIRS=") + (fixed ? "1" : "0")), std::string::npos);
    EXPECT_EQ(make_params(scene, make_device_scene(scene, scene.settings.width, scene.settings.height)).scatter_draw_pairs, fixed ? 1u : 0u);
    return fixed;
  };
  EXPECT_TRUE(paired(load_book_scene("diffuse")));
  EXPECT_TRUE(paired(load_book_scene("specular")));  // Phong reads u0 and u1 only
  EXPECT_FALSE(paired(load_book_scene("glass")));
  Scene roulette = load_book_scene("diffuse");
  roulette.settings.rr_from = 3;
  EXPECT_FALSE(paired(roulette));
  EXPECT_EQ(kernel_build_options(generic_features()).find("CLPT_SCATTER_DRAW_PAIRS"), std::string::npos);
}

}  // namespace
}  // namespace clpt::test
