// The first-hit layers (`--aovs`, kernels/aov.cl, docs/aovs.md) against their closed forms: a
// camera at the origin looking at a Lambertian wall (a triangle pair) with a sphere before it,
// rendered with the grid sampler, whose 16 sub-pixel positions are known, so that every pixel's
// expected albedo, normal and depth is the mean of 16 ray casts done here in double with the
// device's own camera vectors. Then the delta rule (a mirror is looked through, or recorded where
// the path ends on it), emitters, both execution forms alike, the beauty unchanged by the layers,
// and the EXR's channels read back through io/render_file.h.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "device_test_util.h"
#include "io/image_io.h"
#include "io/render_file.h"
#include "kernels/aov_channels.h"
#include "render/aov_set.h"
#include "render_test_util.h"
#include "scene/device_scene.h"
#include "util/error.h"

namespace clpt::test {
namespace {

constexpr int kWidth = 16, kHeight = 12;
constexpr double kWallZ = -6;  // the wall's plane, facing the camera (+z)

Material coloured(MaterialType type, Vec3 reflectance) {
  Material m;
  m.type = type;
  m.reflectance = reflectance;
  return m;
}

// The square [-s, s]^2 in the plane z = `z`, two triangles wound so that the geometric normal is
// (0, 0, facing).
TriangleMesh quad(double z, double s, double facing, const Material& material) {
  TriangleMesh m;
  m.name = "quad";
  m.positions = {{-s, -s, z}, {s, -s, z}, {s, s, z}, {-s, s, z}};
  if (facing > 0)
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
  else
    m.triangles = {{0, 2, 1}, {0, 3, 2}};
  m.material = material;
  return m;
}

Scene base_scene() {
  Scene scene;
  scene.file = "aov-test";
  scene.camera.position = {0, 0, 0};
  scene.camera.look_at = {0, 0, -1};
  scene.camera.up = {0, 1, 0};
  scene.camera.vertical_fov_deg = 40;
  scene.settings.max_bounces = 3;
  return scene;
}

// The wall (reflectance 1/4, 1/2, 3/4: sums of 16 of them are exact in float) and a grey sphere
// before it, left of centre, lit from behind the camera.
constexpr Vec3 kWallColour = {0.25, 0.5, 0.75};
constexpr Vec3 kSphereCentre = {-0.5, 0.25, -4};
constexpr double kSphereRadius = 1;
Scene wall_and_sphere() {
  Scene scene = base_scene();
  scene.meshes.push_back(quad(kWallZ, 30, +1, coloured(MaterialType::Lambertian, kWallColour)));
  Sphere ball;
  ball.name = "ball";
  ball.center = kSphereCentre;
  ball.radius = kSphereRadius;
  ball.material = coloured(MaterialType::Lambertian, {0.5, 0.5, 0.5});
  scene.spheres.push_back(ball);
  // A lamp behind the camera, out of view: a lit (and noisy) beauty, for adaptive sampling.
  Sphere lamp;
  lamp.name = "lamp_behind";
  lamp.center = {0, 0, 3};
  lamp.radius = 0.5;
  lamp.material.type = MaterialType::Emitter;
  lamp.material.emission = {8, 8, 8};
  scene.spheres.push_back(lamp);
  return scene;
}

Film render_aovs(Scene scene, Sampler sampler, ExecutionForm form = ExecutionForm::Megakernel, bool aovs = true,
                 int64_t spp = 16, bool adaptive = false) {
  RenderRequest request = test_request(std::move(scene), kWidth, kHeight, spp, 5, sampler);
  request.form = form;
  request.adaptive = adaptive;
  request.aovs.albedo = request.aovs.normal = request.aovs.depth = aovs;
  RenderReport report;
  return run_render(request, report);
}

using D3 = std::array<double, 3>;
D3 sub(D3 a, D3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(D3 a, D3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 scaled(D3 a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

// The camera ray of pixel (col, row) through the grid sampler's sub-pixel position k, from the
// device's camera vectors (kernels/camera.cl), in double.
D3 camera_direction(const GpuCamera& c, int col, int row, int k) {
  const double sx = ((k & 3) + 0.5) / 4, sy = ((k >> 2) + 0.5) / 4;
  const double fx = (col + sx) / kWidth, fy = (kHeight - 1 - row + sy) / kHeight;
  D3 d;
  for (int i = 0; i < 3; ++i)
    d[size_t(i)] = double(c.sensor_center[i]) + double(c.sensor_right[i]) * (fx - 0.5) + double(c.sensor_up[i]) * (fy - 0.5);
  return scaled(d, 1 / std::sqrt(dot(d, d)));
}

// One sample's layers: albedo, normal, depth.
struct Layers {
  D3 albedo{}, normal{};
  double depth = 0;
  bool ambiguous = false;  // the ray grazes the sphere's rim: float rounding may decide either way
};

Layers cast_wall_and_sphere(D3 d) {
  Layers l;
  const D3 c = {kSphereCentre[0], kSphereCentre[1], kSphereCentre[2]};
  const double b = dot(d, c), disc = b * b - (dot(c, c) - kSphereRadius * kSphereRadius);
  l.ambiguous = std::abs(disc) < 1e-3;
  if (disc > 0 && b - std::sqrt(disc) > 0) {
    l.depth = b - std::sqrt(disc);
    l.normal = scaled(sub(scaled(d, l.depth), c), 1 / kSphereRadius);
    l.albedo = {0.5, 0.5, 0.5};
    return l;
  }
  l.depth = kWallZ / d[2];
  l.normal = {0, 0, 1};
  l.albedo = kWallColour;
  return l;
}

// The film's layer means against the mean of the closed form at the grid's 16 positions.
// Returns the pixels compared.
int expect_layers(const Film& film, const Scene& scene, Layers (*cast)(D3), double depth_tolerance) {
  const DeviceScene ds = make_device_scene(scene, kWidth, kHeight);
  const std::vector<float> means = film.aov_means();
  EXPECT_EQ(means.size(), size_t(kWidth) * kHeight * CLPT_AOV_CHANNELS);
  int compared = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int col = 0; col < kWidth; ++col) {
      Layers sum;
      bool ambiguous = false;
      for (int k = 0; k < 16; ++k) {
        const Layers l = cast(camera_direction(ds.camera, col, row, k));
        ambiguous |= l.ambiguous;
        for (size_t i = 0; i < 3; ++i) {
          sum.albedo[i] += l.albedo[i] / 16;
          sum.normal[i] += l.normal[i] / 16;
        }
        sum.depth += l.depth / 16;
      }
      if (ambiguous) continue;
      ++compared;
      const float* m = &means[(size_t(row) * kWidth + size_t(col)) * CLPT_AOV_CHANNELS];
      const std::string at = "pixel (" + std::to_string(col) + ", " + std::to_string(row) + ")";
      for (size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(m[CLPT_AOV_ALBEDO + i], sum.albedo[i], 1e-6) << at << " albedo " << i;
        EXPECT_NEAR(m[CLPT_AOV_NORMAL + i], sum.normal[i], 2e-5) << at << " normal " << i;
      }
      EXPECT_NEAR(m[CLPT_AOV_DEPTH], sum.depth, depth_tolerance * sum.depth) << at << " depth";
    }
  return compared;
}

TEST(Aovs, WallAndSphereMatchTheClosedForm) {
  const Scene scene = wall_and_sphere();
  const Film film = render_aovs(scene, Sampler::Grid);
  ASSERT_TRUE(film.has_aovs());
  // Float ray casts against the double closed form: a few ulps of the hit distance.
  EXPECT_GT(expect_layers(film, scene, cast_wall_and_sphere, 1e-5), kWidth * kHeight * 3 / 4);
}

// Pixels whose rays all hit the wall: its reflectance exactly, its normal exactly; also under
// adaptive sampling, whose pixels take different numbers of samples (in slots of several passes).
class AovsWall : public ::testing::TestWithParam<bool> {};
TEST_P(AovsWall, LambertianWallAlbedoIsItsReflectanceExactly) {
  const bool adaptive = GetParam();
  const Scene scene = wall_and_sphere();
  const Film film = render_aovs(scene, Sampler::Jitter, ExecutionForm::Megakernel, true, adaptive ? 64 : 16, adaptive);
  const std::vector<float> means = film.aov_means();
  // The right-hand column is far from the sphere (left of centre).
  for (int row = 0; row < kHeight; ++row) {
    const float* m = &means[(size_t(row) * kWidth + kWidth - 1) * CLPT_AOV_CHANNELS];
    EXPECT_EQ(m[CLPT_AOV_ALBEDO + 0], 0.25f);
    EXPECT_EQ(m[CLPT_AOV_ALBEDO + 1], 0.5f);
    EXPECT_EQ(m[CLPT_AOV_ALBEDO + 2], 0.75f);
    EXPECT_EQ(m[CLPT_AOV_NORMAL + 0], 0.0f);
    EXPECT_EQ(m[CLPT_AOV_NORMAL + 1], 0.0f);
    EXPECT_EQ(m[CLPT_AOV_NORMAL + 2], 1.0f);
  }
}
INSTANTIATE_TEST_SUITE_P(Aovs, AovsWall, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "Adaptive" : "Uniform"; });

// A mirror wall in front, a coloured wall behind the camera: the albedo is the mirror's colour
// times the wall's (OIDN's "first non-delta hit"), the normal the back wall's, the depth the
// mirror's. With no bounce left the path ends on the mirror, which is then recorded.
constexpr Vec3 kBackColour = {0.5, 0.25, 1.0};
Scene mirror_room() {
  Scene scene = base_scene();
  scene.meshes.push_back(quad(kWallZ, 30, +1, coloured(MaterialType::Mirror, {0.5, 0.5, 0.5})));
  scene.meshes.push_back(quad(6, 60, -1, coloured(MaterialType::Lambertian, kBackColour)));
  return scene;
}

Layers cast_through_mirror(D3 d) {
  Layers l;
  l.depth = kWallZ / d[2];
  l.normal = {0, 0, -1};
  l.albedo = {0.5 * kBackColour[0], 0.5 * kBackColour[1], 0.5 * kBackColour[2]};
  return l;
}

Layers cast_onto_mirror(D3 d) {
  Layers l;
  l.depth = kWallZ / d[2];
  l.normal = {0, 0, 1};
  l.albedo = {0.5, 0.5, 0.5};
  return l;
}

TEST(Aovs, DeltaSurfacesAreLookedThrough) {
  const Scene scene = mirror_room();
  EXPECT_EQ(expect_layers(render_aovs(scene, Sampler::Grid), scene, cast_through_mirror, 1e-5), kWidth * kHeight);
}

TEST(Aovs, APathEndingOnADeltaSurfaceRecordsIt) {
  Scene scene = mirror_room();
  scene.settings.max_bounces = 0;
  EXPECT_EQ(expect_layers(render_aovs(scene, Sampler::Grid), scene, cast_onto_mirror, 1e-5), kWidth * kHeight);
}

// An emitter's albedo is its emission clamped to [0, 1]; a miss leaves albedo, normal and depth 0.
TEST(Aovs, EmittersAndMisses) {
  Scene scene = base_scene();
  Material light;
  light.type = MaterialType::Emitter;
  light.emission = {4.0, 0.5, 0.0};
  TriangleMesh wall = quad(kWallZ, 1, +1, light);  // covers the image's centre only
  scene.meshes.push_back(wall);
  const std::vector<float> means = render_aovs(scene, Sampler::Grid).aov_means();
  const float* centre = &means[(size_t(kHeight / 2) * kWidth + kWidth / 2) * CLPT_AOV_CHANNELS];
  EXPECT_EQ(centre[CLPT_AOV_ALBEDO + 0], 1.0f);
  EXPECT_EQ(centre[CLPT_AOV_ALBEDO + 1], 0.5f);
  EXPECT_EQ(centre[CLPT_AOV_ALBEDO + 2], 0.0f);
  EXPECT_EQ(centre[CLPT_AOV_NORMAL + 2], 1.0f);
  for (uint32_t c = 0; c < CLPT_AOV_CHANNELS; ++c) EXPECT_EQ(means[c], 0.0f) << "corner pixel, channel " << c;
}

// Same seed, jitter sampler: the megakernel and the wavefront record the same layers, and the
// layers leave the beauty as it was.
TEST(Aovs, BothFormsAgreeAndTheBeautyIsUnchanged) {
  Scene scene = wall_and_sphere();
  scene.meshes.push_back(quad(2, 30, -1, coloured(MaterialType::Mirror, {0.9, 0.9, 0.9})));  // behind the camera
  Material light;
  light.type = MaterialType::Emitter;
  light.emission = {3, 3, 3};
  Sphere lamp;
  lamp.name = "lamp";
  lamp.center = {2, 3, -4};
  lamp.radius = 0.7;
  lamp.material = light;
  scene.spheres.push_back(lamp);
  const Film mk = render_aovs(scene, Sampler::Jitter, ExecutionForm::Megakernel, true, 32);
  const Film wf = render_aovs(scene, Sampler::Jitter, ExecutionForm::Wavefront, true, 32);
  const std::vector<float> a = mk.aov_means(), b = wf.aov_means();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-5 * std::max(1.0f, std::abs(a[i]))) << i;
  const Film plain = render_aovs(scene, Sampler::Jitter, ExecutionForm::Megakernel, false, 32);
  EXPECT_FALSE(plain.has_aovs());
  expect_same_image(mk.mean_rgb(), plain.mean_rgb());
  const Film plain_wf = render_aovs(scene, Sampler::Jitter, ExecutionForm::Wavefront, false, 32);
  expect_same_image(wf.mean_rgb(), plain_wf.mean_rgb());
}

// The EXR holds the layers asked for under io/render_file.h's names, and read_render_file finds
// them; a render without them has none of those channels.
TEST(Aovs, TheExrCarriesTheNamedChannels) {
  const Film film = render_aovs(wall_and_sphere(), Sampler::Grid);
  const std::string dir = std::filesystem::temp_directory_path() / ("clpt_aovs_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  RenderFileInfo info;
  info.version = "test";
  info.aovs = "albedo,normal,depth";
  write_render_file(dir + "/all.exr", film, info);
  const RenderFile all = read_render_file(dir + "/all.exr");
  EXPECT_EQ(all.info.aovs, "albedo,normal,depth");
  const std::vector<float> means = film.aov_means();
  ASSERT_EQ(all.albedo.size(), film.pixel_count() * 3);
  ASSERT_EQ(all.normal.size(), film.pixel_count() * 3);
  ASSERT_EQ(all.depth.size(), film.pixel_count());
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(all.albedo[p * 3 + c], means[p * CLPT_AOV_CHANNELS + CLPT_AOV_ALBEDO + c]);
      EXPECT_EQ(all.normal[p * 3 + c], means[p * CLPT_AOV_CHANNELS + CLPT_AOV_NORMAL + c]);
    }
    EXPECT_EQ(all.depth[p], means[p * CLPT_AOV_CHANNELS + CLPT_AOV_DEPTH]);
  }
  EXPECT_EQ(all.image.mean, film.mean_rgb());

  info.aovs = "depth";
  write_render_file(dir + "/depth.exr", film, info);
  const RenderFile depth = read_render_file(dir + "/depth.exr");
  EXPECT_TRUE(depth.albedo.empty());
  EXPECT_TRUE(depth.normal.empty());
  EXPECT_EQ(depth.depth.size(), film.pixel_count());

  info.aovs = "";
  write_render_file(dir + "/none.exr", film, info);
  const RenderFile none = read_render_file(dir + "/none.exr");
  EXPECT_TRUE(none.albedo.empty() && none.normal.empty() && none.depth.empty());
  EXPECT_TRUE(none.info.aovs.empty());
  std::filesystem::remove_all(dir);
}

TEST(Aovs, ParsedAndPrinted) {
  const AovSet all = parse_aov_set("depth,albedo,normal", "--aovs");
  EXPECT_TRUE(all.albedo && all.normal && all.depth);
  EXPECT_EQ(aov_set_text(all), "albedo,normal,depth");
  EXPECT_EQ(aov_set_text(parse_aov_set("normal", "--aovs")), "normal");
  EXPECT_THROW(parse_aov_set("albedo,nrm", "--aovs"), Error);
  EXPECT_THROW(parse_aov_set("albedo,albedo", "--aovs"), Error);
  EXPECT_THROW(parse_aov_set("", "--aovs"), Error);
}

}  // namespace
}  // namespace clpt::test
