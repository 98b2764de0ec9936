// A tilted normal map against closed forms (docs/textures.md, "Normal maps"): a Lambertian plane
// carrying a constant tangent-space map (a float image, so the tilt is exact up to float
// rounding), under a point light and seen straight down by an orthographic camera, has radiance
// rho / pi I max(0, n' . (L - p)) / |L - p|^3 with n' the mapped normal t x + b y + n z, which
// the host integrates over each pixel in double. The lit region and its brightest spot move
// where the tilt says; in the megakernel, the wavefront and the generic kernel. The opposite
// tilt under the mirrored light gives the mirrored image; a tangent whose handedness w is -1
// (given, or generated from mirrored texture coordinates) mirrors the bitangent, and the test
// tells the two apart. And the house rule: a mapped normal the camera sees from behind is not
// used (the unmapped normal shades), and light below the geometric surface does not reach it
// even where the tilted normal faces it. Thresholds: z of each pixel's own variance (Sidak over
// the pixels) plus float rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "plane_closed_form.h"
#include "render_test_util.h"

namespace clpt::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSize = kPlaneImageSize;

using Normal = std::array<double, 3>;

// The map's texel (RGB) for the tangent-space normal (sin a cos phi, sin a sin phi, cos a), and
// the tangent-space normal the kernel decodes from it: (2 c - 1) of the float values stored.
struct Tilt {
  std::array<float, 3> texel;
  Normal tangent_space;
};
Tilt tilt(double a_deg, double phi_deg) {
  const double a = a_deg * kPi / 180, phi = phi_deg * kPi / 180;
  const double m[3] = {std::sin(a) * std::cos(phi), std::sin(a) * std::sin(phi), std::cos(a)};
  Tilt out{};
  for (int k = 0; k < 3; ++k) {
    out.texel[size_t(k)] = float(0.5 + 0.5 * m[k]);
    out.tangent_space[size_t(k)] = 2.0 * double(out.texel[size_t(k)]) - 1.0;
  }
  return out;
}

// The plane y = 0 (geometric and shading normal +y, no vertex normals), 40 units wide, under an
// orthographic camera at y = 5 whose image's right is +x and whose image's up is -z. Texture
// coordinates: u along +x, v along -z (the generated tangent is +x, the bitangent n x t = -z, w =
// +1); with `mirrored_uvs` v runs along +z instead (w = -1). `tangent_w`: 0 to let clpt generate
// the tangents, else every vertex's tangent is (1, 0, 0, tangent_w).
struct Plane {
  Tilt map;
  bool mirrored_uvs = false;
  double tangent_w = 0;
};
Scene plane_scene(const Plane& p, const PunctualLight& light) {
  Scene scene = lit_plane_scene("normal_map_closed_form");
  TriangleMesh& plane = scene.meshes.back();
  for (const Vec3& q : plane.positions)
    plane.uvs.push_back({(q[0] + 20) / 40, ((p.mirrored_uvs ? q[2] : -q[2]) + 20) / 40});
  if (p.tangent_w != 0) plane.tangents.assign(4, {1, 0, 0, p.tangent_w});
  TextureImage image;
  image.file = "tilt";
  image.width = image.height = 2;
  image.channels = 3;
  image.storage = TexelStorage::Float;
  image.color_space = ColorSpace::Linear;
  for (int i = 0; i < 4; ++i) image.pixels.insert(image.pixels.end(), p.map.texel.begin(), p.map.texel.end());
  scene.images.push_back(image);
  plane.material.textures.normal.image = 0;
  plane.material.textures.normal.where = "plane.material.normal_map";
  scene.lights.push_back(light);
  return scene;
}

// The mapped normal in world space: t = +x, b = w n x t = w (0, 0, -1), n = +y.
Normal world_normal(const Normal& m, double w) {
  const double x = m[0], y = m[1], z = m[2];
  const double length = std::sqrt(x * x + y * y + z * z);
  return {x / length, z / length, -w * y / length};
}

PunctualLight point_light(const Vec3& position, double intensity) {
  PunctualLight l;
  l.name = "point";
  l.type = LightType::Point;
  l.position = position;
  l.intensity = {intensity, intensity, intensity};
  return l;
}

// Irradiance through the shading normal n at the plane's point (x, 0, z): I max(0, n . (L - p)) /
// |L - p|^3, zero where L is below the plane (the geometric side) or n faces away from it.
double point_irradiance(const PunctualLight& l, const Normal& n, double x, double z) {
  const double d[3] = {l.position[0] - x, l.position[1], l.position[2] - z};
  const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double cos_shading = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
  if (d[1] <= 0 || cos_shading <= 0) return 0;
  return l.intensity[0] * cos_shading / (d2 * std::sqrt(d2));
}

// The pixel (row-major) of the closed form's brightest point: where the highlight is.
int brightest_pixel(const PlaneExpected& e) {
  return int(std::max_element(e.mean.begin(), e.mean.end()) - e.mean.begin());
}

// How many pixels two closed forms put further apart than `margin` relative: a check that can
// tell them apart (the tilt and its mirror, the two handednesses) must find many.
int pixels_apart(const PlaneExpected& a, const PlaneExpected& b, double margin) {
  int n = 0;
  for (int i = 0; i < kSize * kSize; ++i) n += std::fabs(a.mean[i] - b.mean[i]) > margin * std::max(a.mean[i], b.mean[i]);
  return n;
}

const PunctualLight kLight = point_light({0.4, 1.5, -0.3}, 3.0);
const Tilt kTilt = tilt(40, 70);  // 40 degrees, mostly towards the bitangent, some towards the tangent

PlaneExpected closed_form(const Tilt& map, double w, const PunctualLight& light) {
  const Normal n = world_normal(map.tangent_space, w);
  return expected_plane_image([&](double x, double z) { return point_irradiance(light, n, x, z); });
}

TEST(NormalMapClosedForm, TiltedMapMovesTheLightWhereTheClosedFormSays) {
  const PlaneExpected expected = closed_form(kTilt, 1, kLight);
  const PlaneExpected flat = expected_plane_image([&](double x, double z) { return point_irradiance(kLight, {0, 1, 0}, x, z); });
  // The tilt moves the brightest spot (by two pixels or more) and the terminator into the image.
  const int moved = brightest_pixel(expected), still = brightest_pixel(flat);
  EXPECT_GE(std::abs(moved % kSize - still % kSize) + std::abs(moved / kSize - still / kSize), 2);
  EXPECT_GT(std::count(expected.mean.begin(), expected.mean.end(), 0.0), kSize);
  const Scene scene = plane_scene({kTilt}, kLight);
  for (const KernelForm& f : kPlaneForms) {
    SCOPED_TRACE(f.name);
    EXPECT_GT(expect_plane_matches(render_plane(scene, f, 32, 3), expected, kSize * kSize * int(std::size(kPlaneForms))), kSize * kSize / 4);
  }
}

// The same tilt mirrored (tangent-space y negated) under the light mirrored in z gives the image
// mirrored top to bottom: against its closed form, and row by row against the first image.
TEST(NormalMapClosedForm, OppositeTiltGivesTheMirroredImage) {
  Tilt opposite = tilt(-40, 70);
  opposite.texel[0] = kTilt.texel[0], opposite.tangent_space[0] = kTilt.tangent_space[0];  // x kept
  PunctualLight mirrored = kLight;
  mirrored.position[2] = -kLight.position[2];
  const PlaneExpected expected = closed_form(opposite, 1, mirrored);
  ASSERT_GT(pixels_apart(expected, closed_form(kTilt, 1, kLight), 0.2), kSize * kSize / 4);
  const PlaneImage a = render_plane(plane_scene({kTilt}, kLight), kMegakernelForm, 32, 5);
  const PlaneImage b = render_plane(plane_scene({opposite}, mirrored), kMegakernelForm, 32, 6);
  EXPECT_GT(expect_plane_matches(b, expected, kSize * kSize * 2), kSize * kSize / 4);
  const double z = sidak_z(kSize * kSize);
  int bad = 0;
  const PlaneExpected first = closed_form(kTilt, 1, kLight);
  for (int row = 0; row < kSize; ++row)
    for (int col = 0; col < kSize; ++col) {
      const int i = row * kSize + col, j = (kSize - 1 - row) * kSize + col;
      if (first.edge[i]) continue;
      const double diff = a.mean[3 * i] - b.mean[3 * j];
      const double tolerance = z * std::sqrt(double(a.variance[3 * i]) + double(b.variance[3 * j])) + 2e-4 * first.mean[i] + 1e-7;
      if (std::fabs(diff) > tolerance && bad++ < 5)
        ADD_FAILURE() << "pixel " << col << "," << row << ": " << a.mean[3 * i] << ", mirrored " << b.mean[3 * j];
    }
  EXPECT_EQ(bad, 0) << "pixels unlike their mirror";
}

// w = -1 mirrors the bitangent: the map's y tilts the normal towards +z instead of -z. Given
// tangents (1, 0, 0, +-1) on the usual texture coordinates, and tangents generated from texture
// coordinates whose v runs the other way (w = -1, the bitangent +z).
TEST(NormalMapClosedForm, HandednessMirrorsTheBitangent) {
  const PlaneExpected right = closed_form(kTilt, 1, kLight), left = closed_form(kTilt, -1, kLight);
  ASSERT_GT(pixels_apart(right, left, 0.2), kSize * kSize / 4);  // the check tells them apart
  const int comparisons = kSize * kSize * 3;
  Plane given_right{kTilt}, given_left{kTilt}, generated_left{kTilt};
  given_right.tangent_w = 1;
  given_left.tangent_w = -1;
  generated_left.mirrored_uvs = true;
  {
    SCOPED_TRACE("given tangents, w = +1");
    EXPECT_GT(expect_plane_matches(render_plane(plane_scene(given_right, kLight), kMegakernelForm, 32, 7), right, comparisons), kSize * kSize / 4);
  }
  {
    SCOPED_TRACE("given tangents, w = -1");
    EXPECT_GT(expect_plane_matches(render_plane(plane_scene(given_left, kLight), kMegakernelForm, 32, 8), left, comparisons), kSize * kSize / 4);
  }
  {
    SCOPED_TRACE("generated tangents, v along +z (w = -1)");
    EXPECT_GT(expect_plane_matches(render_plane(plane_scene(generated_left, kLight), kMegakernelForm, 32, 9), left, comparisons), kSize * kSize / 4);
  }
}

// The house rule (docs/textures.md, "Normal maps": no light below the surface). A map tilted 120
// degrees (towards the bitangent) puts the mapped normal below the plane: the camera, looking
// straight down, sees it from behind, so the unmapped normal (+y) shades, and the image is the
// flat plane's. And light arriving from below the plane, along a direction the 60-degree-tilted
// normal faces (n' . l = 0.72), carries nothing: the image is black, where the mapped normal's
// cosine alone would light it (0.6 / pi 2 0.72 = 0.275).
TEST(NormalMapClosedForm, HouseRuleMapSeenFromBehindAndLightFromBelow) {
  const Tilt behind = tilt(120, 90);
  const PlaneExpected flat = expected_plane_image([&](double x, double z) { return point_irradiance(kLight, {0, 1, 0}, x, z); });
  ASSERT_GT(pixels_apart(flat, closed_form(behind, 1, kLight), 0.2), kSize * kSize / 4);
  for (const KernelForm& f : {kPlaneForms[0], kPlaneForms[2]}) {
    SCOPED_TRACE(std::string(f.name) + ", mapped normal seen from behind");
    EXPECT_GT(expect_plane_matches(render_plane(plane_scene({behind}, kLight), f, 32, 11), flat, kSize * kSize * 4), kSize * kSize / 2);
  }
  PunctualLight below;
  below.name = "sun";
  below.type = LightType::Directional;
  const double norm = std::sqrt(0.25 * 0.25 + 1);
  below.direction = {0, 0.25 / norm, 1 / norm};  // travels up and towards +z: comes from below
  below.intensity = {2, 2, 2};
  const Normal tilted = world_normal(tilt(60, 90).tangent_space, 1);
  const double cos_mapped = -(tilted[1] * below.direction[1] + tilted[2] * below.direction[2]);
  ASSERT_GT(cos_mapped, 0.7);  // the mapped normal faces the light
  for (const KernelForm& f : {kPlaneForms[0], kPlaneForms[2]}) {
    SCOPED_TRACE(std::string(f.name) + ", light from below the plane");
    const PlaneImage image = render_plane(plane_scene({tilt(60, 90)}, below), f, 32, 12);
    EXPECT_EQ(*std::max_element(image.mean.begin(), image.mean.end()), 0.0f);
  }
}

}  // namespace
}  // namespace clpt::test
