// The covering set of kernel variants (host/tools/kernel_variants.h): every value and every pair
// of values is in some variant, the set is the same on every run, and each variant builds what a
// render of its scene would.
#include <gtest/gtest.h>

#include <set>

#include "render_test_util.h"
#include "tools/kernel_variants.h"

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
  // 3 x 3 values of the two largest dimensions need at least 9 variants.
  EXPECT_GE(variants.size(), 9u);
  EXPECT_LE(variants.size(), 14u);
  std::set<std::string> names;
  for (const KernelVariant& v : variants) EXPECT_TRUE(names.insert(v.name()).second) << v.name();
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
    }
    EXPECT_EQ(p.features.lockstep_group > 0,
              v.form() == ExecutionForm::Megakernel && v.megakernel_loop() == MegakernelLoop::Lockstep);
    EXPECT_EQ(scene.settings.rr_from >= 0, v.russian_roulette());
    // A specialised rolled variant builds with its loops rolled; every other keeps the option out.
    const bool rolled = !v.generic() && v.scene_loops() == SceneLoops::Rolled;
    EXPECT_EQ(kernel_build_options(p.features).find("-DCLPT_UNROLL_SCENE_LOOPS=0") != std::string::npos, rolled)
        << v.name();
  }
}

}  // namespace
}  // namespace clpt::test
