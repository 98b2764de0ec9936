// Image textures on spheres (docs/textures.md, "Spheres"): the spherical mapping seen by camera
// rays from known directions, in the megakernel and the wavefront; the device's texture
// coordinates against the documented formula (sphere_texture_coordinates) pixel by pixel; a
// constant texture against the plain colour it stands for; an emission texture on a sphere light
// alike under nee (whose light samples read it, light.cl) and book; the sphere section's order
// when the spheres are hierarchy primitives; a textured sphere beside a vertex-coloured mesh; and
// the refusal of a normal map on a sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "render/render_session.h"
#include "render_test_util.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "util/error.h"

namespace clpt::test {
namespace {

using Rgb = std::array<double, 3>;

// The 5 x 3 globe marker: the top row (the north pole's band) white, the bottom row cyan, the
// middle row red, green, blue, yellow, magenta from left to right (u in fifths).
const Rgb kNorth = {1, 1, 1}, kSouth = {0, 1, 1};
const Rgb kMiddle[5] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}};
constexpr int kMarkerWidth = 5, kMarkerHeight = 3;

Rgb marker_texel(int x, int y) { return y == 0 ? kNorth : y == 2 ? kSouth : kMiddle[x]; }

std::string temp_dir(const std::string& name) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("clpt_sphere_textures_" + name)).string();
  std::filesystem::create_directories(dir);
  return dir;
}

void write_globe_marker(const std::string& dir) {
  std::vector<unsigned char> rgb;
  for (int y = 0; y < kMarkerHeight; ++y)
    for (int x = 0; x < kMarkerWidth; ++x)
      for (double c : marker_texel(x, y)) rgb.push_back(c > 0 ? 255 : 0);
  write_rgb8_image(dir + "/globe.png", kMarkerWidth, kMarkerHeight, rgb);
}

std::string vec(const Vec3& v) {
  return "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + "]";
}

// A unit emitter sphere at the origin whose emission is the marker (nearest), seen along -from
// by an orthographic camera 2.2 units high: a camera ray's radiance is the texel it hits.
Scene globe_scene(const std::string& dir, const Vec3& from, const Vec3& up) {
  const std::string text = "[render]\nmax_bounces = 0\n[camera]\nposition = " + vec({5 * from[0], 5 * from[1], 5 * from[2]}) +
                           "\nlook_at = [0, 0, 0]\nup = " + vec(up) +
                           "\nprojection = \"orthographic\"\nheight = 2.2\n"
                           "[[sphere]]\nname = \"globe\"\ncenter = [0, 0, 0]\nradius = 1\n"
                           "material = { type = \"emitter\", emission = { texture = \"globe.png\", filter = \"nearest\" } }\n";
  return load_scene_string(text, dir + "/globe.toml");
}

Film render(const Scene& scene, ExecutionForm form, int size, int64_t spp, uint64_t seed) {
  RenderRequest request = test_request(scene, size, size, spp, seed);
  request.form = form;
  RenderReport report;
  return run_render(request, report);
}

Vec3 cross3(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 unit(const Vec3& a) {
  const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / l, a[1] / l, a[2] / l};
}

// The marker texel the documented mapping gives at unit normal n (nearest, repeat in u; the
// rows clamped, as v is in [0, 1]).
std::array<int, 2> texel_at(const Vec3& n) {
  const std::array<double, 2> uv = sphere_texture_coordinates(n[0], n[1], n[2]);
  const double u = uv[0] - std::floor(uv[0]);
  const int x = std::min(kMarkerWidth - 1, int(std::floor(u * kMarkerWidth)));
  const int y = std::clamp(int(std::floor((1 - uv[1]) * kMarkerHeight)), 0, kMarkerHeight - 1);
  return {x, y};
}

// What pixel (col, row) of a size x size render of globe_scene(from, up) must show when every
// point of its footprint (an 11 x 11 grid over the pixel, edges included) hits the sphere and
// maps to texels of one colour: that colour; nullopt where the footprint meets the silhouette or
// an edge between colours.
std::optional<Rgb> expected_pixel(const Vec3& from, const Vec3& up, int size, int col, int row) {
  const Vec3 dir = {-from[0], -from[1], -from[2]};
  const Vec3 right = unit(cross3(dir, up));
  const Vec3 top = cross3(right, dir);
  const double height = 2.2, pixel = height / size;
  std::optional<Rgb> colour;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) {
      const double sx = -height / 2 + (col + i / 10.0) * pixel, sy = height / 2 - (row + j / 10.0) * pixel;
      const double r2 = sx * sx + sy * sy;
      if (r2 > 0.97) return std::nullopt;  // near the silhouette
      const double depth = std::sqrt(1 - r2);
      const Vec3 n = {sx * right[0] + sy * top[0] - depth * dir[0], sx * right[1] + sy * top[1] - depth * dir[1],
                      sx * right[2] + sy * top[2] - depth * dir[2]};
      const std::array<int, 2> t = texel_at(n);
      const Rgb c = marker_texel(t[0], t[1]);
      if (colour && *colour != c) return std::nullopt;
      colour = c;
    }
  return colour;
}

struct View {
  const char* name;
  Vec3 from, up;
};
const View kViews[] = {
    {"from +X", {1, 0, 0}, {0, 1, 0}}, {"from -Z", {0, 0, -1}, {0, 1, 0}}, {"from -X", {-1, 0, 0}, {0, 1, 0}},
    {"from +Z", {0, 0, 1}, {0, 1, 0}}, {"from above", {0, 1, 0}, {0, 0, -1}}, {"from below", {0, -1, 0}, {0, 0, 1}},
};

Rgb pixel_of(const std::vector<float>& mean, int size, int col, int row) {
  const size_t at = (size_t(row) * size_t(size) + size_t(col)) * 3;
  return {mean[at], mean[at + 1], mean[at + 2]};
}

void expect_colour(const Rgb& seen, const Rgb& expected, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[size_t(c)], expected[size_t(c)], 1e-4) << what << " channel " << c;
}

// The mapping's landmarks, seen from outside (docs/textures.md): the image's centre column
// (blue) faces -Z, its second (green) +X, its fourth (yellow) -X, its left and right edges meet
// at +Z (magenta to the left of the seam, red to its right: the image reads unmirrored, left to
// right as the camera's right), the top row is the north pole and the bottom row the south.
TEST(SphereTextures, MarkerSeenFromEachSideInBothForms) {
  install_scene_image_reader();
  const std::string dir = temp_dir("landmarks");
  write_globe_marker(dir);
  constexpr int size = 11, centre = 5;
  for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    const std::string f = form == ExecutionForm::Wavefront ? "wavefront " : "megakernel ";
    std::vector<std::vector<float>> images;
    for (const View& v : kViews) images.push_back(render(globe_scene(dir, v.from, v.up), form, size, 4, 1).mean_rgb());
    expect_colour(pixel_of(images[0], size, centre, centre), kMiddle[1], f + "from +X, centre: green");
    expect_colour(pixel_of(images[0], size, centre - 3, centre), kMiddle[0], f + "from +X, left: red");
    expect_colour(pixel_of(images[0], size, centre + 3, centre), kMiddle[1], f + "from +X, right: still green");
    expect_colour(pixel_of(images[1], size, centre, centre), kMiddle[2], f + "from -Z, centre: blue (the image's centre)");
    expect_colour(pixel_of(images[2], size, centre, centre), kMiddle[3], f + "from -X, centre: yellow");
    expect_colour(pixel_of(images[3], size, centre - 2, centre), kMiddle[4], f + "from +Z, left of the seam: magenta");
    expect_colour(pixel_of(images[3], size, centre + 2, centre), kMiddle[0], f + "from +Z, right of the seam: red");
    expect_colour(pixel_of(images[4], size, centre, centre), kNorth, f + "from above: the top row");
    expect_colour(pixel_of(images[0], size, centre, 1), kNorth, f + "from +X, high: the top row");
    expect_colour(pixel_of(images[5], size, centre, centre), kSouth, f + "from below: the bottom row");
    expect_colour(pixel_of(images[0], size, centre, size - 2), kSouth, f + "from +X, low: the bottom row");
  }
}

// Every pixel whose footprint lies inside one texel shows that texel, where the documented
// formula in double (scene/texture.h, sphere_texture_coordinates) puts it: the kernel's float
// coordinates agree with it over the whole visible half of the sphere, from every side.
TEST(SphereTextures, DeviceUvIsTheDocumentedMapping) {
  install_scene_image_reader();
  const std::string dir = temp_dir("formula");
  write_globe_marker(dir);
  constexpr int size = 40;
  for (const View& v : kViews) {
    const std::vector<float> mean = render(globe_scene(dir, v.from, v.up), ExecutionForm::Megakernel, size, 4, 2).mean_rgb();
    int checked = 0;
    for (int row = 0; row < size; ++row)
      for (int col = 0; col < size; ++col) {
        const std::optional<Rgb> expected = expected_pixel(v.from, v.up, size, col, row);
        if (!expected) continue;
        ++checked;
        expect_colour(pixel_of(mean, size, col, row), *expected,
                      std::string(v.name) + " pixel (" + std::to_string(col) + ", " + std::to_string(row) + ")");
      }
    EXPECT_GT(checked, size * size / 3) << v.name;  // most of the disc (area 0.65 of the image)
  }
}

// The book's diffuse room with its left ball's reflectance from a constant image, and its right
// ball a pbr material whose base colour (RGB), metallic (channel 2) and roughness (channel 1)
// come from another: the same image, statistically, as the plain values (same seed), under nee. Each of
// 16 regions agrees within the two renders' variances (Sidak).
TEST(SphereTextures, ConstantTextureRendersAsThePlainColour) {
  Scene plain = load_book_scene("diffuse");
  Scene textured = plain;
  TextureImage image;
  image.file = "constant";
  image.width = 4;
  image.height = 2;
  image.channels = 3;
  image.storage = TexelStorage::Float;
  image.color_space = ColorSpace::Linear;
  const Rgb colour = {0.6, 0.3, 0.15};
  for (int i = 0; i < 8; ++i)
    for (double c : colour) image.pixels.push_back(float(c));
  textured.images.push_back(image);
  // RGB (0.8, 0.35, 0.1): the base colour, roughness 0.35 in G and metallic 0.1 in B (x factors 1)
  TextureImage pbr = image;
  pbr.pixels.clear();
  for (int i = 0; i < 8; ++i)
    for (float c : {0.8f, 0.35f, 0.1f}) pbr.pixels.push_back(c);
  textured.images.push_back(pbr);
  int found = 0;
  for (size_t i = 0; i < plain.spheres.size(); ++i) {
    Material& p = plain.spheres[i].material;
    Material& t = textured.spheres[i].material;
    if (plain.spheres[i].name == "left_ball") {
      ++found;
      p.reflectance = {double(float(0.6)), double(float(0.3)), double(float(0.15))};
      t.reflectance = {1, 1, 1};
      t.textures.base_color.image = 0;
    } else if (plain.spheres[i].name == "right_ball") {
      ++found;
      p.type = t.type = MaterialType::Pbr;
      p.reflectance = {double(0.8f), double(0.35f), double(0.1f)};
      p.metallic = double(0.1f);
      p.roughness = double(0.35f);
      t.reflectance = {1, 1, 1};
      t.metallic = t.roughness = 1;
      t.textures.base_color.image = t.textures.metallic.image = t.textures.roughness.image = 1;
      t.textures.metallic.channel = 2;
      t.textures.roughness.channel = 1;
    }
  }
  ASSERT_EQ(found, 2);
  for (Scene* s : {&plain, &textured}) s->settings.estimator = "nee";
  constexpr int w = 32, h = 24;
  const MeanVarianceImage a = render_for_test(plain, w, h, 64, 5).film.mean_variance();
  const MeanVarianceImage b = render_for_test(textured, w, h, 64, 5).film.mean_variance();
  const double z = sidak_z(16 * 3);
  for (int ry = 0; ry < 4; ++ry)
    for (int rx = 0; rx < 4; ++rx) {
      const RegionStats ra = region_stats(a.mean, a.variance, w, rx * 8, ry * 6, rx * 8 + 8, ry * 6 + 6);
      const RegionStats rb = region_stats(b.mean, b.variance, w, rx * 8, ry * 6, rx * 8 + 8, ry * 6 + 6);
      for (int c = 0; c < 3; ++c)
        EXPECT_LT(std::fabs(ra.mean[c] - rb.mean[c]), z * std::sqrt(ra.variance_of_mean[c] + rb.variance_of_mean[c]) + 1e-6)
            << "region (" << rx << ", " << ry << ") channel " << c << ": plain " << ra.mean[c] << ", textured " << rb.mean[c];
    }
}

// A sphere light whose emission is a 4 x 1 image (red, green, blue, yellow: the quarters of the
// turn from +Z through +X, -Z and -X) lights a floor below it: next-event estimation (which
// reads the texture at its sampled cap points, light.cl) and the book estimator (which finds it
// where a path hits the sphere) converge to the same image, and the floor's quadrants are tinted
// by the faces above them. Were the light samples to see the factor alone, nee's floor would
// come out white-lit.
TEST(SphereTextures, EmissionTextureLightsAlikeUnderBothEstimators) {
  install_scene_image_reader();
  const std::string dir = temp_dir("emission");
  write_rgb8_image(dir + "/faces.png", 4, 1, {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 0});
  const auto scene = [&](const char* estimator) {
    return std::string("[render]\nmax_bounces = 1\nestimator = \"") + estimator + R"("
[camera]
position = [0, 0.15, 0.001]
look_at = [0, 0, 0]
projection = "orthographic"
height = 2
[[sphere]]
name = "floor"
center = [0, -1000, 0]
radius = 1000
material = { type = "lambertian", reflectance = [0.8, 0.8, 0.8] }
[[sphere]]
name = "globe"
center = [0, 0.6, 0]
radius = 0.4
material = { type = "emitter", emission = { texture = "faces.png", filter = "nearest", scale = 4 } }
)";
  };
  constexpr int size = 8;
  const MeanVarianceImage a = render_for_test(load_scene_string(scene("nee"), dir + "/nee.toml"), size, size, 256, 3).film.mean_variance();
  const MeanVarianceImage b = render_for_test(load_scene_string(scene("book"), dir + "/book.toml"), size, size, 512, 4).film.mean_variance();
  const double z = sidak_z(4 * 3);
  double red_minus_blue[4] = {};
  for (int q = 0; q < 4; ++q) {
    const int x0 = (q % 2) * 4, y0 = (q / 2) * 4;
    const RegionStats ra = region_stats(a.mean, a.variance, size, x0, y0, x0 + 4, y0 + 4);
    const RegionStats rb = region_stats(b.mean, b.variance, size, x0, y0, x0 + 4, y0 + 4);
    for (int c = 0; c < 3; ++c)
      EXPECT_LT(std::fabs(ra.mean[c] - rb.mean[c]), z * std::sqrt(ra.variance_of_mean[c] + rb.variance_of_mean[c]) + 1e-6)
          << "quadrant " << q << " channel " << c << ": nee " << ra.mean[c] << ", book " << rb.mean[c];
    red_minus_blue[q] = ra.mean[0] - ra.mean[2];
  }
  // The quadrants differ in tint: the faces of the light above them differ in colour (red and
  // yellow against blue and green).
  const auto [lo, hi] = std::minmax_element(std::begin(red_minus_blue), std::end(red_minus_blue));
  EXPECT_GT(*hi - *lo, 0.1) << "red minus blue per quadrant: " << red_minus_blue[0] << ", " << red_minus_blue[1]
                            << ", " << red_minus_blue[2] << ", " << red_minus_blue[3];
}

// More than 16 spheres make them hierarchy primitives, reordered by the build (device_scene.cpp):
// the sphere section follows the kernels' order. 24 small globes, each its own colour from a
// 1 x 1 image, seen from above; each globe's pixel shows its own colour.
TEST(SphereTextures, SphereSectionFollowsTheHierarchyOrder) {
  install_scene_image_reader();
  const std::string dir = temp_dir("hierarchy");
  std::string text = "[render]\nmax_bounces = 0\n[camera]\nposition = [0, 10, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\n"
                     "projection = \"orthographic\"\nheight = 6\n";
  std::vector<Rgb> colours;
  for (int i = 0; i < 24; ++i) {
    const Rgb c = {((i * 7) % 11) / 10.0, ((i * 3) % 5) / 4.0, (i % 3) / 2.0};
    colours.push_back(c);
    const std::string file = "c" + std::to_string(i) + ".png";
    std::vector<unsigned char> rgb;
    for (double v : c) rgb.push_back(static_cast<unsigned char>(std::lround(v * 255)));
    for (int k = 0; k < 3; ++k) colours.back()[size_t(k)] = rgb[size_t(k)] / 255.0;  // as stored, linear
    write_rgb8_image(dir + "/" + file, 1, 1, rgb);
    const int x = i % 6, z = i / 6;
    text += "[[sphere]]\ncenter = [" + std::to_string(-2.5 + x) + ", 0, " + std::to_string(-1.5 + z) +
            "]\nradius = 0.3\nmaterial = { type = \"emitter\", emission = { texture = \"" + file +
            "\", color_space = \"linear\", filter = \"nearest\" } }\n";
  }
  // 0.125 units a pixel (x to the right, -z up): globe (x, z)'s centre is the corner shared by
  // pixels (8x + 3, 8z + 11) to (8x + 4, 8z + 12), which lie inside its disc (radius 0.3).
  constexpr int size = 48;
  const std::vector<float> mean =
      render(load_scene_string(text, dir + "/many.toml"), ExecutionForm::Megakernel, size, 1, 7).mean_rgb();
  for (int i = 0; i < 24; ++i) {
    const int x = i % 6, z = i / 6;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx)
        expect_colour(pixel_of(mean, size, 8 * x + 3 + dx, 8 * z + 11 + dy), colours[size_t(i)],
                      "globe " + std::to_string(i));
  }
}

// A textured sphere beside a mesh with vertex colours (glTF COLOR_0: the texturing buffer's colors
// section, read for triangle hits only): the sphere's hits read no triangle's colours, in the
// specialised and the generic kernel, and the globe shows its landmarks as alone.
TEST(SphereTextures, BesideAVertexColouredMesh) {
  install_scene_image_reader();
  const std::string dir = temp_dir("colours");
  write_globe_marker(dir);
  Scene scene = globe_scene(dir, {1, 0, 0}, {0, 1, 0});
  TriangleMesh mesh;  // in the image's top-left corner, beside the globe's disc
  mesh.name = "coloured";
  mesh.positions = {{0.5, 0.8, 0.8}, {0.5, 0.8, 1.1}, {0.5, 1.1, 1.1}};
  mesh.triangles = {{0, 1, 2}};
  mesh.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
  mesh.material.type = MaterialType::Emitter;
  mesh.material.emission = {1, 1, 1};
  scene.meshes.push_back(mesh);
  constexpr int size = 11, centre = 5;
  for (bool generic : {false, true}) {
    RenderRequest request = test_request(scene, size, size, 4, scene.settings.seed);
    request.generic_kernel = generic;
    RenderReport report;
    const std::vector<float> mean = run_render(request, report).mean_rgb();
    const std::string k = generic ? "generic: " : "specialised: ";
    expect_colour(pixel_of(mean, size, centre, centre), kMiddle[1], k + "centre: green");
    expect_colour(pixel_of(mean, size, centre - 3, centre), kMiddle[0], k + "left: red");
    expect_colour(pixel_of(mean, size, centre, 1), kNorth, k + "high: the top row");
  }
}

TEST(SphereTextures, NormalMapOnASphereIsRefusedNamingTheKeyAndTheSphere) {
  const std::string text = R"([camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
[[sphere]]
name = "ball"
center = [0, 0, 0]
radius = 1
material = { type = "lambertian", reflectance = [0.5, 0.5, 0.5], normal_map = { texture = "n.png" } }
[[sphere]]
center = [0, 3, 0]
radius = 1
material = { type = "emitter", emission = [1, 1, 1] }
)";
  try {
    load_scene_string(text, "globe.toml");
    FAIL() << "a normal map on a sphere was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("globe.toml:8:", 0), 0u) << m;
    EXPECT_NE(m.find("sphere[0].material.normal_map"), std::string::npos) << m;
    EXPECT_NE(m.find("sphere 'ball'"), std::string::npos) << m;
    EXPECT_EQ(e.code(), ExitCode::BadScene) << m;
  }
}

}  // namespace
}  // namespace clpt::test
