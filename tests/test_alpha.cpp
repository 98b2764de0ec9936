// glTF alphaMode MASK and BLEND (kernels/alpha.cl, docs/gltf.md "Alpha"): a MASK checkerboard seen
// by the camera is the quad or the background, texel for texel; a BLEND quad of alpha 0.3 in front
// of an emitter averages to 0.3 x its radiance + 0.7 x the emitter's; shadows of both through
// next-event estimation agree with BSDF sampling and with reference geometry; every execution form,
// both mesh traversals (the triangle loop and the hierarchy) and the generic kernel agree; the
// loader's defaults and the kernels' specialisation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "device_test_util.h"
#include "gltf_builder.h"
#include "io/image_io.h"
#include "io/png_writer.h"
#include "kernels/kernel_options.h"
#include "quad_camera_scene.h"
#include "render_test_util.h"
#include "scene/scene_loader.h"
#include "scene/texture_load.h"

namespace clpt::test {
namespace {

std::string temp_dir(const std::string& name) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("clpt_alpha_" + name)).string();
  std::filesystem::create_directories(dir);
  return dir;
}

// A 2 x 2 RGBA checkerboard: white, alpha 255 at the top-left and bottom-right texels, 0 elsewhere.
void write_checker(const std::string& path) {
  const std::vector<unsigned char> rgba = {255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 255};
  ImageToWrite image;
  image.width = image.height = 2;
  image.channels = {"R", "G", "B", "A"};
  image.uint8 = true;
  image.pixels = rgba.data();
  ASSERT_EQ(write_png(path, image), "");
}

// A glTF quad with corners `xyz` (4 x 3, counter-clockwise seen from its front), glTF texture
// coordinates (0, 1), (1, 1), (1, 0), (0, 0), and `material`; with `checker`, the checkerboard
// (nearest) as its base colour texture.
GltfBuilder quad(const std::vector<float>& xyz, const nlohmann::json& material, bool checker) {
  GltfBuilder b;
  const int position = b.positions(xyz);
  const int uv = b.accessor(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, 5126, "VEC2");
  const int indices = b.indices({0, 1, 2, 0, 2, 3});
  nlohmann::json m = material;
  if (checker) {
    b.push("images", {{"uri", "checker.png"}});
    b.push("samplers", {{"magFilter", 9728}});
    b.push("textures", {{"source", 0}, {"sampler", 0}});
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  }
  b.push("materials", m);
  b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}}}, {"indices", indices}, {"material", 0}})}});
  return b;
}

// A glTF material: black base colour of alpha `alpha`, emission (0.2, 0.4, 0.6) (none with
// `dark`: a blocker in the shadow scenes, which would otherwise light the floor itself),
// double-sided.
nlohmann::json material(double alpha, const std::string& mode, double cutoff = -1, bool dark = false) {
  nlohmann::json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, alpha}}, {"metallicFactor", 0}}},
                      {"emissiveFactor", dark ? std::vector<double>{0, 0, 0} : std::vector<double>{0.2, 0.4, 0.6}},
                      {"doubleSided", true}};
  if (!mode.empty()) m["alphaMode"] = mode;
  if (cutoff >= 0) m["alphaCutoff"] = cutoff;
  return m;
}
const double kQuadEmission[3] = {0.2, 0.4, 0.6};

const std::vector<float> kFacingCamera = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};

// The shadow scene: a floor y = 0 (reflectance 0.8) lit by an emitting square of side 1 at y = 2
// (radiance 8) through the glTF file `gltf` (a horizontal quad at y = 1, or nothing), seen from
// below that quad (an orthographic camera at y = 0.5 looking down); one bounce, so the floor's
// light is its direct light alone.
Scene shadow_scene(const std::string& dir, const std::string& estimator, const std::string& gltf) {
  std::string text = "[render]\nmax_bounces = 1\nestimator = \"" + estimator + R"("
[camera]
position = [0, 0.5, 0.001]
look_at = [0, 0, 0]
projection = "orthographic"
height = 2
[[mesh]]
vertices = [[-1, 0, 1], [1, 0, 1], [1, 0, -1], [-1, 0, -1]]
quads = [[0, 1, 2, 3]]
material = { type = "lambertian", reflectance = [0.8, 0.8, 0.8] }
[[mesh]]
vertices = [[-0.5, 2, -0.5], [0.5, 2, -0.5], [0.5, 2, 0.5], [-0.5, 2, 0.5]]
quads = [[0, 1, 2, 3]]
material = { type = "emitter", emission = [8, 8, 8] }
)";
  if (!gltf.empty()) text += "[[gltf]]\nfile = \"" + gltf + "\"\n";
  return load_scene_string(text, dir + "/shadow_" + estimator + ".toml");
}
const std::vector<float> kHorizontal = {-1, 1, 1, 1, 1, 1, 1, 1, -1, -1, 1, -1};

// How a test renders: the form, the mesh traversal, the generic kernel.
struct Way {
  const char* name;
  ExecutionForm form;
  SceneLoops loops;  // Auto: on PoCL's CPU device a small mesh's triangle loop; Rolled: the hierarchy
  bool generic;
};
const Way kWays[] = {
    {"megakernel, triangle loop", ExecutionForm::Megakernel, SceneLoops::Auto, false},
    {"megakernel, hierarchy", ExecutionForm::Megakernel, SceneLoops::Rolled, false},
    {"wavefront", ExecutionForm::Wavefront, SceneLoops::Auto, false},
    {"generic megakernel", ExecutionForm::Megakernel, SceneLoops::Auto, true},
};

MeanVarianceImage render(const Scene& scene, const Way& way, int size, int64_t spp, uint64_t seed) {
  RenderRequest request = test_request(scene, size, size, spp, seed, Sampler::Jitter);
  request.form = way.form;
  request.scene_loops = way.loops;
  request.generic_kernel = way.generic;
  RenderReport report;
  return run_render(request, report).mean_variance();
}

// Each quadrant (size / 2 square) of two images agrees within their variances (Sidak over
// `comparisons`); returns the first image's quadrant means (channel 0).
std::array<double, 4> expect_quadrants_agree(const MeanVarianceImage& a, const MeanVarianceImage& b, int size,
                                             int comparisons, const std::string& what, double b_scale = 1) {
  const double z = sidak_z(comparisons);
  std::array<double, 4> means{};
  for (int q = 0; q < 4; ++q) {
    const int h = size / 2, x0 = (q % 2) * h, y0 = (q / 2) * h;
    const RegionStats ra = region_stats(a.mean, a.variance, size, x0, y0, x0 + h, y0 + h);
    const RegionStats rb = region_stats(b.mean, b.variance, size, x0, y0, x0 + h, y0 + h);
    for (int c = 0; c < 3; ++c) {
      const double diff = ra.mean[c] - b_scale * rb.mean[c];
      EXPECT_LT(std::fabs(diff), z * std::sqrt(ra.variance_of_mean[c] + b_scale * b_scale * rb.variance_of_mean[c]) + 1e-6)
          << what << ": quadrant " << q << " channel " << c << ": " << ra.mean[c] << " against " << b_scale * rb.mean[c];
    }
    means[size_t(q)] = ra.mean[0];
  }
  return means;
}

TEST(GltfAlpha, MaskCheckerboardIsTheQuadOrTheBackgroundInEveryForm) {
  install_scene_image_reader();
  const std::string dir = temp_dir("mask_camera");
  write_checker(dir + "/checker.png");
  std::ofstream(dir + "/quad.gltf") << quad(kFacingCamera, material(1, "MASK"), true).gltf_embedded();
  const Scene scene = quad_camera_scene(dir);
  EXPECT_TRUE(features_for_scene(scene).alpha);
  for (const Way& way : kWays) {
    const MeanVarianceImage image = render(scene, way, 4, 4, 1);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const bool cut = (x < 2) != (y < 2);  // the top-right and bottom-left texels have alpha 0
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(image.mean[size_t(y * 4 + x) * 3 + size_t(c)], cut ? 1.0 : kQuadEmission[c], 1e-4)
              << way.name << ": pixel (" << x << ", " << y << ") channel " << c;
      }
  }
}

// alphaCutoff: 0.5 by default (a factor of 0.6 stays, and the material compiles no alpha at all),
// explicit 0.7 cuts it; OPAQUE ignores even an alpha of 0.
TEST(GltfAlpha, CutoffDefaultAndExplicitAndOpaqueIgnoresAlpha) {
  install_scene_image_reader();
  const std::string dir = temp_dir("cutoff");
  const struct {
    nlohmann::json material;
    bool cut;
    bool compiled;
    double cutoff;
  } cases[] = {{material(0.6, "MASK"), false, false, 0.5},
               {material(0.6, "MASK", 0.7), true, true, 0.7},
               {material(0, "OPAQUE"), false, false, 0.5},
               {material(0, ""), false, false, 0.5}};
  for (const auto& k : cases) {
    std::ofstream(dir + "/quad.gltf") << quad(kFacingCamera, k.material, false).gltf_embedded();
    const Scene scene = quad_camera_scene(dir);
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_DOUBLE_EQ(scene.meshes[1].material.textures.alpha_cutoff, k.cutoff) << k.material.dump();
    EXPECT_EQ(features_for_scene(scene).alpha, k.compiled) << k.material.dump();
    EXPECT_EQ(kernel_build_options(features_for_scene(scene)).find("CLPT_HAS_ALPHA") != std::string::npos, k.compiled);
    const MeanVarianceImage image = render(scene, kWays[0], 2, 1, 1);
    for (size_t i = 0; i < image.mean.size(); ++i)
      EXPECT_NEAR(image.mean[i], k.cut ? 1.0 : kQuadEmission[i % 3], 1e-4) << k.material.dump() << " value " << i;
  }
}

// BLEND, alpha 0.3, in front of an emitter: the image's mean is 0.3 x the quad's emission + 0.7 x
// the emitter's, within the estimator's own variance (each sample is one or the other).
TEST(GltfAlpha, BlendQuadAveragesToItsCoverageInEveryForm) {
  install_scene_image_reader();
  const std::string dir = temp_dir("blend_camera");
  std::ofstream(dir + "/quad.gltf") << quad(kFacingCamera, material(0.3, "BLEND"), false).gltf_embedded();
  const Scene scene = quad_camera_scene(dir);
  const double z = sidak_z(int(std::size(kWays)) * 3);
  uint64_t seed = 11;
  for (const Way& way : kWays) {
    const MeanVarianceImage image = render(scene, way, 8, 64, seed++);
    const RegionStats s = region_stats(image.mean, image.variance, 8, 0, 0, 8, 8);
    for (int c = 0; c < 3; ++c) {
      const double expected = 0.3 * kQuadEmission[c] + 0.7;
      // The sample variance of a two-valued sample: 0.21 (1 - e)^2 per sample, 8 x 8 x 64 samples.
      const double sigma = std::sqrt(0.21 * (1 - kQuadEmission[c]) * (1 - kQuadEmission[c]) / (64.0 * 64.0));
      EXPECT_LT(std::fabs(s.mean[c] - expected), z * sigma) << way.name << " channel " << c << ": " << s.mean[c];
      EXPECT_NEAR(std::sqrt(s.variance_of_mean[c]), sigma, 0.2 * sigma) << way.name << ": the film's own variance";
    }
  }
}

// A MASK checkerboard between an area light and a floor casts the shadow of its opaque cells: the
// same image as two opaque quads in their place (next-event estimation), and under BSDF sampling
// alone the same as under next-event estimation (shadow rays and BSDF rays pass the same holes).
TEST(GltfAlpha, MaskShadowIsTheShadowOfItsOpaqueCells) {
  install_scene_image_reader();
  const std::string dir = temp_dir("mask_shadow");
  write_checker(dir + "/checker.png");
  std::ofstream(dir + "/mask.gltf") << quad(kHorizontal, material(1, "MASK", -1, true), true).gltf_embedded();
  // The opaque cells: texel (0, 0) is x, z in [-1, 0]; texel (1, 1) is x, z in [0, 1].
  GltfBuilder cells;
  const int position = cells.positions({-1, 1, 0, 0, 1, 0, 0, 1, -1, -1, 1, -1, 0, 1, 1, 1, 1, 1, 1, 1, 0, 0, 1, 0});
  const int indices = cells.indices({0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7});
  cells.push("materials", material(1, "", -1, true));
  cells.node({{"mesh", cells.mesh({{"attributes", {{"POSITION", position}}}, {"indices", indices}, {"material", 0}})}});
  std::ofstream(dir + "/cells.gltf") << cells.gltf_embedded();
  const MeanVarianceImage reference = render(shadow_scene(dir, "nee", "cells.gltf"), kWays[0], 8, 256, 21);
  const MeanVarianceImage book = render(shadow_scene(dir, "book", "mask.gltf"), kWays[0], 8, 256, 22);
  uint64_t seed = 23;
  const int comparisons = (int(std::size(kWays)) + 1) * 12;
  for (const Way& way : kWays) {
    const MeanVarianceImage nee = render(shadow_scene(dir, "nee", "mask.gltf"), way, 8, 256, seed++);
    const auto means = expect_quadrants_agree(nee, reference, 8, comparisons, std::string(way.name) + ", against the opaque cells");
    // The pattern: two quadrants in the cells' shadow, two lit through the holes.
    const double lit = std::max({means[0], means[1], means[2], means[3]});
    const double dark = std::min({means[0], means[1], means[2], means[3]});
    EXPECT_GT(lit, 1.3 * dark) << way.name;
    if (&way == &kWays[0]) expect_quadrants_agree(nee, book, 8, comparisons, "nee against book");
  }
}

// A BLEND quad of alpha 0.3 between the light and the floor passes 0.7 of the light in expectation:
// the floor is 0.7 x the floor without the quad, under next-event estimation and BSDF sampling alike.
TEST(GltfAlpha, BlendShadowPassesOneMinusAlphaOfTheLight) {
  install_scene_image_reader();
  const std::string dir = temp_dir("blend_shadow");
  std::ofstream(dir + "/blend.gltf") << quad(kHorizontal, material(0.3, "BLEND", -1, true), false).gltf_embedded();
  const MeanVarianceImage open = render(shadow_scene(dir, "nee", ""), kWays[0], 8, 256, 31);
  const MeanVarianceImage book = render(shadow_scene(dir, "book", "blend.gltf"), kWays[0], 8, 256, 32);
  const int comparisons = 4 * 12;
  uint64_t seed = 33;
  for (const Way& way : {kWays[0], kWays[2], kWays[3]}) {
    const MeanVarianceImage nee = render(shadow_scene(dir, "nee", "blend.gltf"), way, 8, 256, seed++);
    expect_quadrants_agree(nee, open, 8, comparisons, std::string(way.name) + ", against 0.7 x no quad", 0.7);
    if (way.generic) expect_quadrants_agree(nee, book, 8, comparisons, "nee against book");
  }
}

// Same seed, same image: the coverage decisions are a function of (seed, pixel, sample, bounce,
// triangle), not of the form or the pass split.
TEST(GltfAlpha, BlendDecisionsAreTheSameInBothForms) {
  install_scene_image_reader();
  const std::string dir = temp_dir("blend_forms");
  std::ofstream(dir + "/quad.gltf") << quad(kFacingCamera, material(0.5, "BLEND"), false).gltf_embedded();
  const Scene scene = quad_camera_scene(dir);
  const MeanVarianceImage a = render(scene, kWays[0], 8, 4, 5);
  const MeanVarianceImage b = render(scene, kWays[1], 8, 4, 5);
  const MeanVarianceImage c = render(scene, kWays[2], 8, 4, 5);
  expect_same_image(a.mean, b.mean);
  expect_same_image(a.mean, c.mean);
}

// A texture's colour is read as the file stores it, not premultiplied by its alpha (OIIO's
// default for PNG): a white texel of alpha 128 stays white, its alpha 128 / 255.
TEST(GltfAlpha, TextureColoursAreNotPremultipliedByAlpha) {
  install_scene_image_reader();
  const std::string path = temp_dir("unassociated") + "/half.png";
  const std::vector<unsigned char> rgba = {255, 255, 255, 128};
  ImageToWrite image;
  image.width = image.height = 1;
  image.channels = {"R", "G", "B", "A"};
  image.uint8 = true;
  image.pixels = rgba.data();
  ASSERT_EQ(write_png(path, image), "");
  std::vector<TextureImage> images;
  const int index = load_texture_image(images, path, path, ColorSpace::Srgb, "test");
  const TextureImage& t = images[size_t(index)];
  ASSERT_EQ(t.channels, 4);
  EXPECT_NEAR(t.pixels[0], 1.0, 1e-6);
  EXPECT_NEAR(t.pixels[2], 1.0, 1e-6);
  EXPECT_NEAR(t.pixels[3], 128.0 / 255.0, 1e-6);
}

}  // namespace
}  // namespace clpt::test
