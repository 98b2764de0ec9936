// Host side of the numerical extremes: scene transforms, the scene writer (what
// `clpt scene-transform` writes must load back as the same scene) and the safe-range model.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "device_test_util.h"
#include "extreme_scenes.h"
#include "render_test_util.h"
#include "scene/precision_range.h"
#include "scene/scene_loader.h"
#include "scene/scene_transform.h"
#include "scene/scene_writer.h"

namespace clpt::test {
namespace {

TEST(SceneTransform, ScaleMultipliesEveryLengthAndKeepsDirections) {
  const Scene unit = unit_book_scene();
  const Scene big = scale_scene(unit, 1e6);
  ASSERT_EQ(big.spheres.size(), unit.spheres.size());
  for (size_t i = 0; i < unit.spheres.size(); ++i) {
    EXPECT_EQ(big.spheres[i].radius, unit.spheres[i].radius * 1e6);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(big.spheres[i].center[k], unit.spheres[i].center[k] * 1e6);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(big.camera.position[k], unit.camera.position[k] * 1e6);
    EXPECT_EQ(big.camera.look_at[k], unit.camera.look_at[k] * 1e6);
    EXPECT_EQ(big.camera.up[k], unit.camera.up[k]);
  }
  EXPECT_EQ(big.camera.vertical_fov_deg, unit.camera.vertical_fov_deg);
}

TEST(SceneTransform, TranslateMovesCentresAndCameraButNotRadii) {
  const Scene unit = unit_book_scene();
  const Scene moved = translate_scene(unit, {1e7, -2e5, 3});
  for (size_t i = 0; i < unit.spheres.size(); ++i) {
    EXPECT_EQ(moved.spheres[i].radius, unit.spheres[i].radius);
    EXPECT_EQ(moved.spheres[i].center[0], unit.spheres[i].center[0] + 1e7);
    EXPECT_EQ(moved.spheres[i].center[1], unit.spheres[i].center[1] - 2e5);
  }
  EXPECT_EQ(moved.camera.position[2], unit.camera.position[2] + 3);
  EXPECT_EQ(moved.camera.look_at[0], unit.camera.look_at[0] + 1e7);
}

TEST(SceneTransform, RejectsFactorsThatAreNotPositiveAndFinite) {
  const Scene unit = unit_book_scene();
  EXPECT_THROW(scale_scene(unit, 0), std::invalid_argument);
  EXPECT_THROW(scale_scene(unit, -1), std::invalid_argument);
  EXPECT_THROW(scale_scene(unit, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(translate_scene(unit, Vec3{std::nan(""), 0, 0}), std::invalid_argument);
  EXPECT_THROW(scale_emission(unit, 0), std::invalid_argument);
}

// Every material type, and values (1.2345e-4 scale, 1e5 offset) that are not short decimals.
TEST(SceneWriter, WrittenScenesLoadBackAsTheSameDoubles) {
  for (const char* name : {"diffuse", "specular", "glass"}) {
    const Scene original = translate_scene(scale_scene(load_book_scene(name), 1.2345e-4), {1e5, 3.3e4, -7.1});
    const Scene back = load_scene_string(scene_to_toml(original, "a header\nof two lines"), "written.toml");
    ASSERT_EQ(back.spheres.size(), original.spheres.size()) << name;
    for (size_t i = 0; i < original.spheres.size(); ++i) {
      const Sphere &a = original.spheres[i], &b = back.spheres[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.radius, b.radius) << name << " " << a.name;
      EXPECT_EQ(a.center, b.center) << name << " " << a.name;
      EXPECT_EQ(a.material.type, b.material.type);
      EXPECT_EQ(a.material.reflectance, b.material.reflectance);
      EXPECT_EQ(a.material.emission, b.material.emission);
      EXPECT_EQ(a.material.phong_exponent, b.material.phong_exponent);
      EXPECT_EQ(a.material.ior, b.material.ior);
    }
    EXPECT_EQ(back.camera.position, original.camera.position);
    EXPECT_EQ(back.camera.look_at, original.camera.look_at);
    EXPECT_EQ(back.camera.up, original.camera.up);
    EXPECT_EQ(back.camera.vertical_fov_deg, original.camera.vertical_fov_deg);
    EXPECT_EQ(back.settings.spp, original.settings.spp);
    EXPECT_EQ(back.settings.sampler, original.settings.sampler);
    EXPECT_EQ(back.settings.max_bounces, original.settings.max_bounces);
    EXPECT_EQ(back.settings.estimator, original.settings.estimator);
  }
}

// The committed example scenes are what `clpt scene-transform` makes of scenes/diffuse.toml.
TEST(SceneWriter, CommittedExtremeScenesAreTransformsOfTheBookScene) {
  const Scene unit = unit_book_scene();
  const Scene far = load_scene_file(source_dir() + "/scenes/extremes/diffuse_translate_1e7.toml");
  const Scene expected = translate_scene(unit, {1e7, 1e7, 1e7});
  for (size_t i = 0; i < unit.spheres.size(); ++i) EXPECT_EQ(far.spheres[i].center, expected.spheres[i].center);
  const Scene tiny = load_scene_file(source_dir() + "/scenes/extremes/diffuse_scale_1e-4.toml");
  EXPECT_EQ(tiny.spheres[0].radius, scale_scene(unit, 1e-4).spheres[0].radius);
}

TEST(PrecisionRange, BookScenesAreInsideTheProvenRange) {
  for (const char* name : {"diffuse", "specular", "glass"})
    for (Precision p : {Precision::Robust, Precision::Double}) {
      EXPECT_TRUE(precision_range_warnings(load_book_scene(name), p).empty()) << name << " " << precision_name(p);
      EXPECT_LT(worst_sphere_precision(load_book_scene(name), p).relative_error, 1e-5);
    }
}

// Scaling keeps every ratio of lengths: the estimate must not move (beyond double rounding).
// Translation only adds the host's double rounding of world coordinates.
TEST(PrecisionRange, ScaleAndTranslationBarelyChangeTheEstimate) {
  const Scene unit = unit_book_scene();
  const double base = worst_sphere_precision(unit, Precision::Robust).relative_error;
  for (double s : {1e-4, 1e6})
    EXPECT_NEAR(worst_sphere_precision(scale_scene(unit, s), Precision::Robust).relative_error, base, 1e-6 * base);
  const Scene far = translate_scene(unit, {1e7, 1e7, 1e7});
  EXPECT_NEAR(worst_sphere_precision(far, Precision::Robust).relative_error, base, 1e-8);
  EXPECT_TRUE(precision_range_warnings(far, Precision::Robust).empty());
  // ... until double rounding of the world coordinates reaches float's own error.
  EXPECT_FALSE(precision_range_warnings(translate_scene(unit, {1e16, 0, 0}), Precision::Robust).empty());
}

const char* kSpeckScene = R"(
[camera]
position = [0.0, 1.0, 5.0]
look_at = [0.0, 1.0, 0.0]

[[sphere]]
name = "light"
center = [0.0, 50.0, 0.0]
radius = 10.0
material = { type = "emitter", emission = [4.0, 4.0, 4.0] }

[[sphere]]
name = "speck"
center = [0.0, 1.0, -3000.0]
radius = 0.01
material = { type = "lambertian", reflectance = [0.7, 0.7, 0.7] }
)";

TEST(PrecisionRange, TinySphereFarAwayWarnsNamingItAndItsLine) {
  const Scene scene = load_scene_string(kSpeckScene, "speck.toml");
  const std::vector<std::string> w = precision_range_warnings(scene, Precision::Robust);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("speck.toml:12:"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("sphere 'speck'"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("--precision double"), std::string::npos) << w[0];
  // Double's unit roundoff is 2^29 times smaller: the same scene is well inside its range.
  EXPECT_TRUE(precision_range_warnings(scene, Precision::Double).empty());
}

// The fast preset's discriminant b'^2 - c' cancels for a small sphere far away: the book's scene
// stays in range, a unit ball 1e4 away does not, though robust takes it.
TEST(PrecisionRange, FastEstimateIncludesTheDiscriminantCancellation) {
  const Scene unit = unit_book_scene();
  EXPECT_TRUE(precision_range_warnings(unit, Precision::Fast).empty());
  EXPECT_GT(worst_sphere_precision(unit, Precision::Fast).relative_error,
            worst_sphere_precision(unit, Precision::Robust).relative_error);
  Scene far = unit;
  far.spheres[6].center = {-2, 1, -1e4};  // the left ball, pushed 1e4 away
  EXPECT_TRUE(precision_range_warnings(far, Precision::Robust).empty());
  const std::vector<std::string> w = precision_range_warnings(far, Precision::Fast);
  ASSERT_FALSE(w.empty());
  EXPECT_NE(w[0].find("sphere '" + far.spheres[6].name + "'"), std::string::npos) << w[0];
}

TEST(PrecisionRange, EmissionBeyondTheFilmsFloatRangeWarns) {
  const Scene unit = unit_book_scene();
  EXPECT_TRUE(precision_range_warnings(scale_emission(unit, 1e8 / 8), Precision::Robust).empty());
  const std::vector<std::string> w = precision_range_warnings(scale_emission(unit, 1e20 / 8), Precision::Robust);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("sphere 'light': emission 1e+20"), std::string::npos) << w[0];
}

}  // namespace
}  // namespace clpt::test
