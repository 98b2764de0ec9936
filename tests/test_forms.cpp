// Execution forms and kernel variants agree on the same device and seed: the megakernel (with its
// per-path and its lockstep loop) and the wavefront (with few or many paths in flight), and the
// scene-specialised and generic kernels, and rolled and unrolled scene loops, give the same image
// up to float rounding, as do two work-group sizes (a different contraction of a*b+c can send a rare path elsewhere, hence the 99%
// criterion rather than 100%).
#include <gtest/gtest.h>

#include <cmath>

#include "device_test_util.h"
#include "mesh_test_util.h"
#include "kernels/kernel_options.h"
#include "render_test_util.h"
#include "render/render_plan.h"
#include "scene/device_scene.h"
#include "scene/loop_spheres.h"
#include "scene/scene_loader.h"

namespace clpt::test {
namespace {

struct Variant {
  ExecutionForm form = ExecutionForm::Megakernel;
  uint32_t paths_in_flight = 0;
  bool generic = false;
  size_t local_size = 0;  // 0: the form's default
  MegakernelLoop loop = MegakernelLoop::Auto;
  std::string estimator = "";  // "": the scene's
  SceneLoops scene_loops = SceneLoops::Auto;
  Sampler sampler = Sampler::Jitter;
  bool meshes = false;  // the mesh scene (with_meshes) instead of the book scene
  bool adaptive = false;
  uint64_t spp = 32;
  CpuVectorBits cpu_vector_bits = CpuVectorBits::Auto;
  SphereReads sphere_reads = SphereReads::Auto;
};

// The book scene with triangles and a hierarchy: its left ball replaced by a tessellated sphere
// with shading normals, a mirror box of triangles beside the right ball, and 40 small balls on
// the floor (more than kMaxLoopSpheres: the spheres become hierarchy primitives too).
void with_meshes(Scene& scene) {
  for (size_t i = 0; i < scene.spheres.size(); ++i)
    if (scene.spheres[i].name == "left_ball") {
      scene.meshes.push_back(tessellated_sphere(scene.spheres[i].center, 1.0, 24, 32, scene.spheres[i].material, true));
      scene.spheres.erase(scene.spheres.begin() + long(i));
      break;
    }
  scene.meshes.push_back(closed_box({3.2, 0.0, -1.0}, {4.2, 1.5, 0.0}, mirror(0.9)));
  for (int k = 0; k < 40; ++k) {
    Sphere s;
    s.name = "pebble" + std::to_string(k);
    s.radius = 0.1;
    s.center = {-2.5 + 0.25 * (k % 20), 0.1, 1.5 + 0.3 * (k / 20)};
    s.material = lambertian(0.3 + 0.01 * k);
    scene.spheres.push_back(s);
  }
}

std::vector<float> render_variant(const std::string& scene_name, const Variant& v) {
  return render_book_variant(scene_name, 77, [&](RenderRequest& request) {
    request.form = v.form;
    request.paths_in_flight = v.paths_in_flight;
    request.generic_kernel = v.generic;
    request.local_size = v.local_size;
    request.megakernel_loop = v.loop;
    request.scene_loops = v.scene_loops;
    if (!v.estimator.empty()) request.scene.settings.estimator = v.estimator;
    request.scene.settings.sampler = v.sampler;
    if (v.meshes) with_meshes(request.scene);
    request.adaptive = v.adaptive;
    request.scene.settings.spp = int(v.spp);
    request.cpu_vector_bits = v.cpu_vector_bits;
    request.sphere_reads = v.sphere_reads;
  });
}

class FormsAgree : public ::testing::TestWithParam<std::string> {};

TEST_P(FormsAgree, MegakernelEqualsWavefront) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Megakernel}),
                    render_variant(GetParam(), {ExecutionForm::Wavefront}));
}

TEST_P(FormsAgree, WavefrontWith64PathsInFlightEqualsDefault) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Wavefront, 64}),
                    render_variant(GetParam(), {ExecutionForm::Wavefront, 0}));
}

TEST_P(FormsAgree, SpecialisedKernelEqualsGeneric) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false}),
                    render_variant(GetParam(), {ExecutionForm::Megakernel, 0, true}));
}

TEST_P(FormsAgree, TwoWorkGroupSizesGiveTheSameImage) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 8}),
                    render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 64}));
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Wavefront, 0, false, 32}),
                    render_variant(GetParam(), {ExecutionForm::Wavefront, 0, false, 128}));
}

// Kernel options that change how the sphere loop and the vector lanes are compiled, not the
// materials: checked on the two book scenes whose materials go beyond the diffuse scene's
// (Lambertian and an emitter, in both): Phong in one, glass in the other. Each pair compiles
// programs no other test needs, which with PoCL's cache empty (CI) are most of their time.
class FormOptionsAgree : public FormsAgree {};

// The per-path loop is what GPUs run; on PoCL it must give the lockstep loop's image, for both
// estimators (nee's shadow rays run inside the same lockstep iteration).
TEST_P(FormOptionsAgree, PerPathLoopEqualsLockstepLoop) {
  for (const char* estimator : {"book", "nee"}) {
    SCOPED_TRACE(estimator);
    expect_same_image(
        render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 0, MegakernelLoop::PerPath, estimator}),
        render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 0, MegakernelLoop::Lockstep, estimator}));
  }
}

// Rolled sphere and light loops are what GPUs build (kernel_options.cpp); on PoCL they must give
// the unrolled loops' image in both forms, for both estimators (nee traces a shadow ray through
// the same loop and sums its light pdf over the light loop).
TEST_P(FormOptionsAgree, RolledSceneLoopsEqualUnrolled) {
  for (const char* estimator : {"book", "nee"}) {
    SCOPED_TRACE(estimator);
    for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
      Variant rolled{form, 0, false, 0, MegakernelLoop::Auto, estimator, SceneLoops::Rolled};
      Variant unrolled = rolled;
      unrolled.scene_loops = SceneLoops::Unrolled;
      expect_same_image(render_variant(GetParam(), rolled), render_variant(GetParam(), unrolled));
    }
  }
}

// 512-bit kernels (kernels/cpu_tuning.h) run each path's arithmetic as the 256-bit ones do, 16
// lanes at a time instead of 8: the same image in both forms, for both estimators. Only where the
// test device takes them (PoCL on an x86 CPU with AVX-512); elsewhere the option is refused, which
// KernelOptions.CpuVectorBits512IsRefusedWhereTheDeviceCannotTakeIt checks.
TEST_P(FormOptionsAgree, WideCpuVectorsEqualDefault) {
  if (!device_takes_512_bit_vectors(test_device().device()))
    GTEST_SKIP() << "the test device is not PoCL on an x86 CPU with AVX-512";
  for (const char* estimator : {"book", "nee"}) {
    SCOPED_TRACE(estimator);
    for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
      Variant wide{form, 0, false, 0, MegakernelLoop::Auto, estimator};
      wide.cpu_vector_bits = CpuVectorBits::Bits512;
      Variant narrow = wide;
      narrow.cpu_vector_bits = CpuVectorBits::Bits256;
      expect_same_image(render_variant(GetParam(), wide), render_variant(GetParam(), narrow));
    }
  }
}

// The hit sphere read by selects over the loop's spheres, with the lockstep state in local memory
// (--sphere-reads selects, kernels/maths.cl CLPT_NO_FAST_GATHER), gives the image of indexed
// reads: both forms, both estimators, the grid sampler too (its camera folds to no draw). On the
// glass scene only: 16 programs a scene, and the reads are of the sphere records, which every
// scene's materials share (OclgrindSphereReads.* checks the selects on Oclgrind as well).
class SphereReadsAgree : public FormsAgree {};

TEST_P(SphereReadsAgree, SphereReadsBySelectEqualIndexed) {
  for (const char* estimator : {"book", "nee"}) {
    SCOPED_TRACE(estimator);
    for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
      for (Sampler sampler : {Sampler::Jitter, Sampler::Grid}) {
        Variant selects{form, 0, false, 0, MegakernelLoop::Auto, estimator};
        selects.sampler = sampler;
        selects.spp = 16;
        selects.sphere_reads = SphereReads::Selects;
        Variant indexed = selects;
        indexed.sphere_reads = SphereReads::Indexed;
        expect_same_image(render_variant(GetParam(), selects), render_variant(GetParam(), indexed));
      }
    }
  }
}

// The Sobol sampler is counter-addressed like jitter: both forms, for both estimators, draw the
// same numbers for every path.
TEST_P(FormsAgree, SobolMegakernelEqualsWavefront) {
  for (const char* estimator : {"book", "nee"}) {
    SCOPED_TRACE(estimator);
    Variant mega{ExecutionForm::Megakernel, 0, false, 0, MegakernelLoop::Auto, estimator};
    mega.sampler = Sampler::Sobol;
    Variant wave = mega;
    wave.form = ExecutionForm::Wavefront;
    expect_same_image(render_variant(GetParam(), mega), render_variant(GetParam(), wave));
  }
}

// Adaptive sampling's passes (slots of one pixel and its first sample each, kernels/film.cl) in
// both forms: 64 spp, so that rounds after the uniform start hand out slots.
TEST_P(FormsAgree, AdaptiveMegakernelEqualsWavefront) {
  for (Sampler sampler : {Sampler::Jitter, Sampler::Sobol}) {
    SCOPED_TRACE(sampler_name(sampler));
    Variant mega{ExecutionForm::Megakernel, 0, false, 0, MegakernelLoop::Auto, "nee"};
    mega.sampler = sampler;
    mega.adaptive = true;
    mega.spp = 64;
    Variant wave = mega;
    wave.form = ExecutionForm::Wavefront;
    expect_same_image(render_variant(GetParam(), mega), render_variant(GetParam(), wave));
  }
}

// A lockstep group of 100 does not divide the launches (48 x 36 pixels x 32 samples): the last
// group runs dead copies, which must store nothing.
TEST_P(FormsAgree, LockstepGroupThatDoesNotDivideTheLaunch) {
  expect_same_image(
      render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 100, MegakernelLoop::Lockstep}),
      render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 0, MegakernelLoop::Lockstep}));
}

// Triangles, shading normals, a mirror, spheres in the hierarchy: both forms traverse it alike,
// and the generic kernel (which reads counts at run time) agrees with the specialised one.
TEST(FormsAgreeOnMeshes, MegakernelEqualsWavefront) {
  for (const char* estimator : {"book", "nee"}) {
    Variant mega, wave;
    mega.meshes = wave.meshes = true;
    mega.estimator = wave.estimator = estimator;
    wave.form = ExecutionForm::Wavefront;
    expect_same_image(render_variant("diffuse", mega), render_variant("diffuse", wave));
  }
}

TEST(FormsAgreeOnMeshes, SpecialisedKernelEqualsGeneric) {
  Variant specialised, generic;
  specialised.meshes = generic.meshes = true;
  specialised.estimator = generic.estimator = "nee";
  generic.generic = true;
  expect_same_image(render_variant("diffuse", specialised), render_variant("diffuse", generic));
}

// The Cornell box under nee: its light is two emitting triangles, sampled by next-event
// estimation (CLPT_HAS_TRIANGLE_LIGHTS). Both forms and both megakernel loops run the same stage
// functions, and the generic kernel (run-time light count, the whole list in the sphere-light
// loop) agrees with the specialised one.
TEST(FormsAgreeOnAreaLights, MegakernelLoopsWavefrontAndGenericAgree) {
  const auto render = [](ExecutionForm form, MegakernelLoop loop, bool generic) {
    Variant v;
    v.form = form;
    v.loop = loop;
    v.generic = generic;
    v.estimator = "nee";
    return render_variant("cornell-box", v);
  };
  const std::vector<float> lockstep = render(ExecutionForm::Megakernel, MegakernelLoop::Lockstep, false);
  expect_same_image(lockstep, render(ExecutionForm::Megakernel, MegakernelLoop::PerPath, false));
  expect_same_image(lockstep, render(ExecutionForm::Wavefront, MegakernelLoop::Auto, false));
  expect_same_image(lockstep, render(ExecutionForm::Megakernel, MegakernelLoop::Lockstep, true));
}

INSTANTIATE_TEST_SUITE_P(BookScenes, FormsAgree, ::testing::Values("diffuse", "specular", "glass"));
INSTANTIATE_TEST_SUITE_P(BookScenes, FormOptionsAgree, ::testing::Values("specular", "glass"));
INSTANTIATE_TEST_SUITE_P(BookScenes, SphereReadsAgree, ::testing::Values("glass"));

}  // namespace
}  // namespace clpt::test

namespace clpt::test {
namespace {

// A small mesh's triangles in the unrolled loop (CLPT_TRIANGLE_COUNT, kernels/triangle_loop.cl:
// CPUs with their 16 lanes set) against the hierarchy's traversal (rolled scene loops, the GPUs'
// shape, or the generic kernel): the same closest hits and shadow rays, so the same image. The
// Cornell box (32 triangles, a triangle light) and the book's room with a mirror box of 12
// triangles beside its 8 spheres (both loops in one kernel).
// The loop's cap (kMaxLoopTriangles, 32: the unrolled body's cold PoCL build grows faster than
// its triangles, docs/performance.md "Fixed costs"): the Cornell box's 32 triangles are in the
// loop, one triangle more sends the scene to the hierarchy.
TEST(TriangleLoop, CapIsTheCornellBoxsCount) {
  Scene scene = load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/cornell-box.toml");
  EXPECT_EQ(loop_triangle_count(scene), 32);
  TriangleMesh extra = scene.meshes.back();
  extra.triangles.resize(1);
  scene.meshes.push_back(extra);
  EXPECT_EQ(loop_triangle_count(scene), 0);
  KernelFeatures f = features_for_scene(scene);
  f.cpu_vector_lanes = 16;
  f.unroll_scene_loops = true;
  EXPECT_FALSE(f.triangles_in_loop());
  EXPECT_NE(kernel_build_options(f).find("-DCLPT_HAS_BVH=1"), std::string::npos);
  // The hierarchy's leaves: four triangles in one vector test with PoCL's 16 lanes set (the
  // default, named nowhere), one at a time elsewhere (kernels/bvh.cl, CLPT_WIDE_LEAF_TEST).
  EXPECT_EQ(kernel_build_options(f).find("CLPT_WIDE_LEAF_TEST"), std::string::npos);
  f.precision = Precision::Double;  // one at a time: the vector test's cold build costs double most
  EXPECT_NE(kernel_build_options(f).find("-DCLPT_WIDE_LEAF_TEST=0"), std::string::npos);
  f.precision = Precision::Robust;
  f.cpu_vector_lanes = 0;
  EXPECT_NE(kernel_build_options(f).find("-DCLPT_WIDE_LEAF_TEST=0"), std::string::npos);
}

TEST(TriangleLoop, EqualsTheHierarchy) {
  KernelFeatures f = features_for_scene(load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/cornell-box.toml"));
  f.cpu_vector_lanes = 16;
  f.unroll_scene_loops = true;
  EXPECT_TRUE(f.triangles_in_loop());
  EXPECT_NE(kernel_build_options(f).find("-DCLPT_TRIANGLE_COUNT=32"), std::string::npos);
  EXPECT_NE(kernel_build_options(f).find("-DCLPT_HAS_BVH=0"), std::string::npos);
  f.unroll_scene_loops = false;
  EXPECT_FALSE(f.triangles_in_loop());
  EXPECT_EQ(kernel_build_options(f).find("CLPT_TRIANGLE_COUNT"), std::string::npos);
  EXPECT_NE(kernel_build_options(f).find("-DCLPT_HAS_BVH=1"), std::string::npos);

  Variant loop, tree;
  loop.estimator = tree.estimator = "nee";
  loop.loop = tree.loop = MegakernelLoop::Lockstep;
  tree.scene_loops = SceneLoops::Rolled;
  expect_same_image(render_variant("cornell-box", loop), render_variant("cornell-box", tree));

  const auto room = [](bool generic) {
    return render_book_variant("diffuse", 77, [&](RenderRequest& request) {
      request.generic_kernel = generic;
      request.scene.settings.estimator = "nee";
      request.scene.meshes.push_back(closed_box({3.2, 0.0, -1.0}, {4.2, 1.5, 0.0}, mirror(0.9)));
      request.scene.settings.spp = 32;
    });
  };
  expect_same_image(room(false), room(true));
}

TEST(TriangleLoop, MeshesOfLargeTrianglesStayInTheLoopBesideTheHierarchy) {
  const Scene scene = cornell_box_with_ball(load_book_scene("cornell-box"));
  const std::vector<bool> in_loop = loop_meshes(scene);
  ASSERT_EQ(in_loop.size(), 7u);
  for (size_t i = 0; i < 7; ++i)
    EXPECT_EQ(in_loop[i], scene.meshes[i].name != "light" && scene.meshes[i].name != "tessellated sphere") << scene.meshes[i].name;
  EXPECT_EQ(loop_triangle_count(scene), 10);
  EXPECT_TRUE(hierarchy_triangles(scene));

  KernelFeatures f = features_for_scene(scene);
  f.cpu_vector_lanes = 16;
  f.unroll_scene_loops = true;
  EXPECT_TRUE(f.loop_beside_hierarchy());
  const std::string options = kernel_build_options(f);
  EXPECT_NE(options.find("-DCLPT_TRIANGLE_COUNT=10"), std::string::npos);
  EXPECT_NE(options.find("-DCLPT_HAS_BVH=1"), std::string::npos);
  EXPECT_NE(options.find("-DCLPT_BVH_ROOT=1"), std::string::npos);
  f.unroll_scene_loops = false;  // the GPUs' shape: the whole hierarchy from its root
  EXPECT_EQ(kernel_build_options(f).find("CLPT_BVH_ROOT"), std::string::npos);
  EXPECT_EQ(kernel_build_options(f).find("CLPT_TRIANGLE_COUNT"), std::string::npos);

  // The device scene: the loop's triangles first (the five meshes' 10, told by their size), the
  // root's slot 0 the hierarchy of the others from node 1, its slot 1 that of the loop's.
  const DeviceScene ds = make_device_scene(scene, 64, 64);
  ASSERT_EQ(ds.loop_triangles, 10u);
  for (uint32_t i = 0; i < ds.triangles.size(); ++i) {
    const GpuTriangle& t = ds.triangles[i];
    const double e1[3] = {double(t.v1[0]) - t.v0[0], double(t.v1[1]) - t.v0[1], double(t.v1[2]) - t.v0[2]};
    const double e2[3] = {double(t.v2[0]) - t.v0[0], double(t.v2[1]) - t.v0[1], double(t.v2[2]) - t.v0[2]};
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double area = 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    EXPECT_EQ(i < 10, area > 1e5) << i << ": area " << area;  // a wall's half: about 550 x 550 / 2
  }
  const GpuBvhNode& root = ds.bvh.nodes.at(0);
  EXPECT_EQ(root.count[0], 0u);
  EXPECT_EQ(root.child[0], 1u);
  EXPECT_EQ(root.count[1], 0u);
  // Each subtree's leaves: exactly the triangles of its side, each once.
  const auto leaves_of = [&](uint32_t start) {
    std::vector<int> seen(ds.triangles.size(), 0);
    std::vector<uint32_t> todo{start};
    while (!todo.empty()) {
      const GpuBvhNode& n = ds.bvh.nodes.at(todo.back());
      todo.pop_back();
      for (int k = 0; k < CLPT_BVH_WIDTH; ++k) {
        if (!(n.lower_x[k] <= n.upper_x[k])) continue;
        if (n.count[k] == 0u) {
          todo.push_back(n.child[k]);
        } else {
          for (uint32_t t = n.child[k]; t < n.child[k] + (n.count[k] & CLPT_BVH_COUNT_MASK); ++t) ++seen.at(t);
        }
      }
    }
    return seen;
  };
  const std::vector<int> rest = leaves_of(1), loop = leaves_of(root.child[1]);
  for (size_t t = 0; t < ds.triangles.size(); ++t) {
    EXPECT_EQ(rest[t], t < 10 ? 0 : 1) << t;
    EXPECT_EQ(loop[t], t < 10 ? 1 : 0) << t;
  }

  // The plan: the lockstep megakernel keeps the loop beside the hierarchy (the rule's choice on a
  // CPU), the wavefront traverses everything (its intersect stage would run the loop scalar).
  RenderRequest request;
  request.scene = scene;
  const DeviceInfo& device = test_device().device();
  const RenderPlan plan = plan_render(request, {device});
  if (device.is_cpu) {
    EXPECT_EQ(plan.devices.front().form, ExecutionForm::Megakernel);
  }
  request.form = ExecutionForm::Wavefront;
  const RenderPlan wavefront = plan_render(request, {device});
  EXPECT_FALSE(wavefront.devices.front().features.loop_beside_hierarchy());
  EXPECT_EQ(kernel_build_options(wavefront.devices.front().features).find("CLPT_BVH_ROOT"), std::string::npos);

  // The same image, same seed: the loop and the hierarchy below it (lockstep megakernel), the
  // whole hierarchy (rolled scene loops; the wavefront; the generic kernel).
  const auto render = [](const Variant& v) {
    return render_book_variant("cornell-box", 77, [&](RenderRequest& r) {
      r.scene = cornell_box_with_ball(r.scene);
      r.scene.settings.spp = 16;
      r.form = v.form;
      r.generic_kernel = v.generic;
      r.megakernel_loop = v.loop;
      r.scene_loops = v.scene_loops;
    });
  };
  Variant loop_variant, whole;
  loop_variant.loop = whole.loop = MegakernelLoop::Lockstep;
  whole.scene_loops = SceneLoops::Rolled;
  const std::vector<float> with_loop = render(loop_variant);
  expect_same_image(with_loop, render(whole));
  expect_same_image(with_loop, render({ExecutionForm::Wavefront}));
  Variant generic;
  generic.generic = true;
  expect_same_image(with_loop, render(generic));
}

// Only meshes of large triangles go to the loop, whole, while it has room: a scene of similar
// triangles has none there; a mesh too large for the loop's room stays in the hierarchy; with the
// spheres in the hierarchy, no mesh is in the loop.
TEST(TriangleLoop, OnlyLargeTrianglesWholeMeshesWithinTheCap) {
  Scene scene;
  scene.meshes.push_back(tessellated_sphere({0, 0, 0}, 1, 8, 12, lambertian(0.5)));
  scene.meshes.push_back(tessellated_sphere({3, 0, 0}, 1, 8, 12, lambertian(0.5)));
  EXPECT_EQ(loop_triangle_count(scene), 0);
  EXPECT_TRUE(hierarchy_triangles(scene));
  TriangleMesh floor;
  floor.name = "floor";
  floor.positions = {{-50, -1, -50}, {50, -1, -50}, {50, -1, 50}, {-50, -1, 50}};
  floor.triangles = {{0, 2, 1}, {0, 3, 2}};
  floor.material = lambertian(0.5);
  scene.meshes.push_back(floor);
  EXPECT_EQ(loop_triangle_count(scene), 2);
  // A grid of 36 large triangles (more than kMaxLoopTriangles): it does not fit, the floor does.
  TriangleMesh wall;
  wall.name = "wall";
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 3; ++j) wall.positions.push_back({-60.0 + 40 * i, -1.0 + 40 * j, -60.0});
  for (uint32_t i = 0; i < 3; ++i)
    for (uint32_t j = 0; j < 3; ++j) {
      const uint32_t a = i * 4 + j;
      for (int twice = 0; twice < 2; ++twice) {
        wall.triangles.push_back({a, a + 4, a + 5});
        wall.triangles.push_back({a, a + 5, a + 1});
      }
    }
  wall.material = lambertian(0.5);
  ASSERT_GT(wall.triangles.size(), size_t(kMaxLoopTriangles));
  scene.meshes.push_back(wall);
  const std::vector<bool> in_loop = loop_meshes(scene);
  EXPECT_FALSE(in_loop[3]);
  EXPECT_TRUE(in_loop[2]);
  EXPECT_EQ(loop_triangle_count(scene), 2);
  for (int k = 0; k <= kMaxLoopSpheres; ++k) {
    Sphere s;
    s.name = "s" + std::to_string(k);
    s.center = {double(k), 5, 0};
    s.radius = 0.2;
    s.material = lambertian(0.5);
    scene.spheres.push_back(s);
  }
  EXPECT_EQ(loop_triangle_count(scene), 0);
}

}  // namespace
}  // namespace clpt::test
