#include "extreme_scenes.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include "mesh_test_util.h"
#include "render_test_util.h"
#include "scene/scene_transform.h"

namespace clpt::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string format_power(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

Sphere make_sphere(const std::string& name, const Vec3& center, double radius, MaterialType type, double value) {
  Sphere s;
  s.name = name;
  s.center = center;
  s.radius = radius;
  s.material.type = type;
  if (type == MaterialType::Emitter) s.material.emission = {value, value, value};
  else s.material.reflectance = {value, value, value};
  return s;
}

Scene analytic_scene(const std::string& name) {
  Scene scene;
  scene.file = name;
  return scene;
}

}  // namespace

Scene unit_book_scene() { return load_book_scene("diffuse"); }

Extreme scaled_book(double factor) {
  Extreme e;
  e.name = "scale " + format_power(factor);
  e.scene = scale_scene(unit_book_scene(), factor);
  return e;
}

Extreme translated_book(double offset) {
  Extreme e;
  e.name = "translate " + format_power(offset);
  e.scene = translate_scene(unit_book_scene(), {offset, offset, offset});
  return e;
}

Extreme scaled_translated_book(double factor, double offset) {
  Extreme e;
  e.name = "scale " + format_power(factor) + ", translate " + format_power(offset);
  e.scene = translate_scene(scale_scene(unit_book_scene(), factor), {offset, offset, offset});
  return e;
}

Extreme book_with_emission(double emission) {
  Extreme e;
  e.name = "emission " + format_power(emission);
  const double book_emission = 8.0;  // scenes/diffuse.toml's light
  e.image_factor = emission / book_emission;
  e.scene = scale_emission(unit_book_scene(), e.image_factor);
  return e;
}

// The book's light (a cap of a radius-100 sphere under the ceiling) replaced by a ball of radius
// 1e-3 hanging 0.5 below the ceiling, against the same room lit by a ball of radius 0.1 at the
// same centre with 1e4 times less radiance: a sphere light's irradiance at a point that sees all
// of it is pi L r^2 cos / d^2, the same for both, so the rooms' images agree except where the
// light itself shows (the light regions are skipped). Without next-event estimation a path hits
// the tiny light with probability ~1e-7: only meaningful with the nee estimator.
Extreme tiny_light() {
  auto room_lit_by = [](double radius, double emission) {
    Scene scene = unit_book_scene();
    for (Sphere& s : scene.spheres)
      if (s.material.type == MaterialType::Emitter)
        s = make_sphere("hanging_light", {0, 3.5, 0}, radius, MaterialType::Emitter, emission);
    scene.settings.estimator = "nee";
    return scene;
  };
  Extreme e;
  e.name = "tiny light (r 1e-3)";
  e.scene = room_lit_by(1e-3, 1e6);
  e.reference_name = "light r 0.1";
  e.reference = room_lit_by(0.1, 1e2);
  e.skip_regions = {"light", "light_wide", "ceiling"};
  e.needs_nee = true;
  return e;
}

// A Lambertian ball of radius 1 at distance D on the camera's axis, inside an emitting enclosure
// around both; the field of view is set so the ball's image is a disc of radius H/4.
Extreme small_sphere_far(double distance_over_radius) {
  Extreme e;
  e.name = "small sphere, distance/radius " + format_power(distance_over_radius);
  e.check = ExtremeCheck::SmallSphere;
  e.width = 80;
  e.height = 60;
  e.spp = 64;
  e.expected = 2.0;
  e.albedo = 0.5;
  const double d = distance_over_radius;
  e.scene = analytic_scene("small sphere far away");
  e.scene.camera.position = {0, 0, d};
  e.scene.camera.look_at = {0, 0, 0};
  const double alpha = std::asin(1.0 / d);  // angular radius of the ball
  const double half_fov = std::atan(2 * std::tan(alpha));
  e.scene.camera.vertical_fov_deg = 2 * half_fov * 180 / kPi;
  e.disc_radius_px = std::tan(alpha) / std::tan(half_fov) * e.height / 2;
  e.scene.spheres = {make_sphere("enclosure", {0, 0, d / 2}, d, MaterialType::Emitter, e.expected),
                     make_sphere("far_ball", {0, 0, 0}, 1, MaterialType::Lambertian, e.albedo)};
  return e;
}

// The same framing with a glass ball (ior 1.5, reflectance 1): invisible in the enclosure, every
// sample exactly Le up to the float rounding of the radiance scales 1/1.5^2 and 1.5^2. A hit
// point that lands outside the ball when the ray should be inside (or the reverse) applies the
// scale twice: the pixel is off by a factor 2.25. This is the far-sphere check that sees hit-point
// errors, not only silhouettes.
Extreme glass_ball_far(double distance_over_radius) {
  Extreme e = small_sphere_far(distance_over_radius);
  e.name = "glass ball, distance/radius " + format_power(distance_over_radius);
  e.check = ExtremeCheck::Uniform;
  e.tolerance = 1e-5;
  e.scene.spheres[1].name = "far_glass_ball";
  e.scene.spheres[1].material.type = MaterialType::Glass;
  e.scene.spheres[1].material.reflectance = {1, 1, 1};
  e.scene.spheres[1].material.ior = 1.5;
  e.scene.settings.max_bounces = 1000;
  return e;
}

// A camera at height h above the book's floor (a sphere of radius 1e5), looking horizontally
// 10 units ahead, in an emitting enclosure of radius 1000 around it: the floor fills the lower
// half of the image up to a horizon within 0.02 pixel of the middle.
Extreme grazing_camera(double height_over_view) {
  Extreme e;
  e.name = "camera grazing the floor, height " + format_power(height_over_view * 10);
  e.check = ExtremeCheck::Horizon;
  e.width = 80;
  e.height = 60;
  e.spp = 16;
  e.expected = 2.0;
  e.albedo = 0.5;
  const double h = height_over_view * 10;
  e.scene = analytic_scene("grazing camera");
  e.scene.camera.position = {0, h, 0};
  e.scene.camera.look_at = {0, h, -10};
  e.scene.spheres = {make_sphere("enclosure", {0, h, 0}, 1000, MaterialType::Emitter, e.expected),
                     make_sphere("floor", {0, -1e5, 0}, 1e5, MaterialType::Lambertian, e.albedo)};
  return e;
}

// Camera inside a Lambertian sphere of albedo 1 and radius 1 (scaled and translated), with an
// emitter of radius 0.5 at its centre: from any wall point a cosine-weighted direction hits the
// emitter with probability (0.5/1)^2, so within 1000 bounces every path ends there (it misses
// with probability 0.75^1000) and every sample is exactly Le.
Extreme albedo_one_furnace(double factor, double offset) {
  Extreme e;
  e.name = "albedo-1 furnace";
  if (factor != 1 || offset != 0)
    e.name += ", scale " + format_power(factor) + ", translate " + format_power(offset);
  e.check = ExtremeCheck::Uniform;
  e.width = 40;
  e.height = 30;
  e.spp = 16;
  e.expected = 1.5;
  Scene s = analytic_scene("albedo-1 furnace");
  s.camera.position = {0.2, 0.1, 0.75};
  s.camera.look_at = {0, 0, 0};
  s.settings.max_bounces = 1000;
  s.spheres = {make_sphere("white_room", {0, 0, 0}, 1, MaterialType::Lambertian, 1.0),
               make_sphere("light", {0, 0, 0}, 0.5, MaterialType::Emitter, e.expected)};
  e.scene = translate_scene(scale_scene(s, factor), {offset, offset, offset});
  return e;
}

// A 2x2 image inside an emitting sphere: every sample is exactly `emission`, so only the
// accumulation of the film (float per pass, double across passes) can err.
Extreme long_accumulation(double emission, int64_t spp) {
  Extreme e;
  e.name = "accumulation of " + format_power(double(spp)) + " spp of " + format_power(emission);
  e.check = ExtremeCheck::Uniform;
  e.width = 2;
  e.height = 2;
  e.spp = spp;
  e.megakernel = true;
  e.expected = emission;
  Scene s = analytic_scene("long accumulation");
  s.camera.position = {0, 0, 0};
  s.camera.look_at = {0, 0, -1};
  s.spheres = {make_sphere("enclosure", {0, 0, 0}, 10, MaterialType::Emitter, emission)};
  e.scene = s;
  return e;
}

bool mesh_scene_available(const std::string& name) {
  if (name != "torus-knot") return true;  // the Cornell box is inline
  return bool(std::ifstream(std::string(CLPT_SOURCE_DIR) + "/scenes/meshes/torus_knot.ply"));
}

Extreme transformed_mesh_scene(const std::string& name, double factor, double offset) {
  Extreme e;
  e.name = name == "cornell-box" ? "Cornell box" : name == "torus-knot" ? "torus knot" : name;
  if (name == "cornell-box-ball") {
    e.name = "Cornell box with a ball";
    e.reference = cornell_box_with_ball(load_book_scene("cornell-box"));
    e.build_option = "-DCLPT_BVH_ROOT=1";  // the walls in the loop beside the hierarchy
  } else {
    e.reference = load_book_scene(name);
  }
  e.reference_name = e.name;
  if (factor != 1) e.name += ", scale " + format_power(factor);
  if (offset != 0) e.name += ", translate " + format_power(offset);
  e.scene = translate_scene(scale_scene(e.reference, factor), {offset, offset, offset});
  e.width = 80;
  e.height = 60;
  e.spp = 64;
  for (int by = 0; by < 4; ++by)
    for (int bx = 0; bx < 4; ++bx)
      e.regions.push_back({"block " + std::to_string(bx) + "," + std::to_string(by), bx * e.width / 4,
                           by * e.height / 4, (bx + 1) * e.width / 4, (by + 1) * e.height / 4});
  return e;
}

std::vector<Extreme> all_extremes() {
  std::vector<Extreme> all;
  for (double s : {1e-4, 1e-2, 1e2, 1e4, 1e6}) all.push_back(scaled_book(s));
  for (double t : {1e2, 1e4, 1e5, 1e6, 1e7}) all.push_back(translated_book(t));
  all.push_back(scaled_translated_book(1e-4, 1e5));
  for (double le : {1e-6, 1e8}) all.push_back(book_with_emission(le));
  all.push_back(tiny_light());
  for (double d : {1e2, 1e3, 1e4, 1e5, 1e6}) all.push_back(small_sphere_far(d));
  for (double d : {1e2, 1e3, 1e4, 1e5, 1e6}) all.push_back(glass_ball_far(d));
  for (double h : {1e-4, 1e-6}) all.push_back(grazing_camera(h));
  all.push_back(albedo_one_furnace(1, 0));
  all.push_back(albedo_one_furnace(1e6, 1e7));
  all.push_back(long_accumulation(0.75, 10'000'000));
  // 0.7 is not dyadic: a sequential float sum of a pass came out 4.0e-5 low; film.cl sums in blocks of 16.
  all.push_back(long_accumulation(0.7, 10'000'000));
  // Meshes (issue 35): the Cornell box in millimetres, moved and scaled, and the torus knot.
  all.push_back(transformed_mesh_scene("cornell-box", 1, 1e6));
  all.push_back(transformed_mesh_scene("cornell-box", 1e-4, 0));
  all.push_back(transformed_mesh_scene("cornell-box", 1e4, 0));
  all.push_back(transformed_mesh_scene("cornell-box", 1e-4, 1e6));
  all.push_back(transformed_mesh_scene("cornell-box-ball", 1, 1e6));
  all.push_back(transformed_mesh_scene("cornell-box-ball", 1e-4, 0));
  all.push_back(transformed_mesh_scene("cornell-box-ball", 1e-4, 1e6));
  if (mesh_scene_available("torus-knot")) {
    all.push_back(transformed_mesh_scene("torus-knot", 1, 1e6));
    all.push_back(transformed_mesh_scene("torus-knot", 1e-4, 1e6));
  }
  return all;
}

}  // namespace clpt::test
