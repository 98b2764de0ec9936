// Float32 sphere intersection on the device, at the cases docs/numerics.md measured as failing for
// the textbook formula: a unit sphere far away, the book's radius-1e5 walls and its unit balls
// (hit distance, and new rays re-leaving a surface without hitting it again), and the corners
// where walls meet. The reference is the same geometry in double precision on the host.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "device_test_util.h"
#include "scene/device_scene.h"
#include "scene/scene_loader.h"

namespace clpt::test {
namespace {

struct RayD {
  Vec3 o, d;
  int skip = -1;  // sphere the ray leaves on its outer side, as the renderer passes it
};

double dotd(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 subd(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 unit(const Vec3& a) {
  const double l = std::sqrt(dotd(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

// Double-precision closest hit > t_min (world coordinates), or (inf, -1).
std::pair<double, int> reference_hit(const Scene& scene, const RayD& ray, double t_min) {
  std::pair<double, int> best{INFINITY, -1};
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const Vec3 oc = subd(s.center, ray.o);
    const double b = dotd(oc, ray.d);
    const Vec3 l = {oc[0] - b * ray.d[0], oc[1] - b * ray.d[1], oc[2] - b * ray.d[2]};
    const double disc = s.radius * s.radius - dotd(l, l);
    if (disc < 0) continue;
    const double h = std::sqrt(disc);
    for (double t : {b - h, b + h})
      if (t > t_min && t < best.first) best = {t, int(i)};
  }
  return best;
}

// Runs the device's scene_intersect on rays given in world coordinates (made camera-relative as
// the renderer does). Returns (t, sphere) per ray.
std::vector<cl_float2> device_hits(const Scene& scene, const std::vector<RayD>& rays) {
  const DeviceScene ds = make_device_scene(scene, 4, 3);
  std::vector<cl_float4> packed;
  for (const RayD& r : rays) {
    const Vec3 o = subd(r.o, scene.camera.position);
    packed.push_back({{float(o[0]), float(o[1]), float(o[2]), float(r.skip)}});
    packed.push_back({{float(r.d[0]), float(r.d[1]), float(r.d[2]), 0}});
  }
  Kernel kernel(test_program("probe_stages.cl"), "probe_intersect", test_device().where());
  Buffer spheres = upload(ds.spheres);
  Buffer in = upload(packed);
  Buffer out(test_device(), rays.size() * sizeof(cl_float2), CL_MEM_WRITE_ONLY, "hits");
  kernel.set_arg(0, spheres);
  kernel.set_arg(1, cl_uint(ds.spheres.size()));
  kernel.set_arg(2, in);
  kernel.set_arg(3, ds.ray_epsilon);
  kernel.set_arg(4, out);
  test_device().launch(kernel, rays.size(), 0, "probe_intersect");
  return download<cl_float2>(out, rays.size());
}

Scene book_scene() { return load_scene_file(source_dir() + "/scenes/diffuse.toml"); }

// Cosine-distributed direction around n, as Lambertian scattering draws them (normal plus a
// uniform point on the unit sphere).
Vec3 random_cosine_direction(std::mt19937& rng, const Vec3& n) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 v = unit({g(rng), g(rng), g(rng)});
    const Vec3 w = {n[0] + v[0], n[1] + v[1], n[2] + v[2]};
    if (dotd(w, w) > 1e-12) return unit(w);
  }
}

// docs/numerics.md: the textbook formula got 46% of hit/miss answers wrong on a unit sphere 1e4 away.
TEST(SphereIntersect, UnitSphereFarAway) {
  Scene scene;
  scene.camera.position = {0, 0, 0};
  scene.camera.look_at = {0, 0, -1};
  Sphere s;
  s.center = {0.3, -0.2, -1e4};
  s.radius = 1;
  scene.spheres = {s};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> offset(-1.5, 1.5);
  std::vector<RayD> rays;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 target = {s.center[0] + offset(rng), s.center[1] + offset(rng), s.center[2]};
    // Directions as the device will see them (float), so both sides test the same ray.
    Vec3 d = unit(target);
    d = {double(float(d[0])), double(float(d[1])), double(float(d[2]))};
    rays.push_back({{0, 0, 0}, unit(d)});
  }
  const auto hits = device_hits(scene, rays);
  int wrong = 0, decided = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Vec3 oc = s.center;
    const double b = dotd(oc, rays[i].d);
    const double miss_distance = std::sqrt(std::max(0.0, dotd(oc, oc) - b * b));
    if (std::abs(miss_distance - s.radius) < 1e-3) continue;  // within float reach of the silhouette
    ++decided;
    const bool ref_hit = miss_distance < s.radius;
    const bool dev_hit = hits[i].s[1] == 0.0f;
    if (ref_hit != dev_hit) ++wrong;
    if (ref_hit && dev_hit) {
      const double t_ref = b - std::sqrt(s.radius * s.radius - miss_distance * miss_distance);
      EXPECT_NEAR(hits[i].s[0], t_ref, 2e-6 * t_ref);
    }
  }
  EXPECT_GT(decided, 19000);
  EXPECT_EQ(wrong, 0);
}

// Camera rays onto the book's walls and balls: distance within float rounding of the double answer.
TEST(SphereIntersect, BookSceneHitDistances) {
  const Scene scene = book_scene();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-2.99, 8.99), y(0.01, 3.99), z(-2.99, 6.0);
  std::vector<RayD> rays;
  for (int i = 0; i < 20000; ++i)
    rays.push_back({scene.camera.position, unit(subd({x(rng), y(rng), z(rng)}, scene.camera.position))});
  const auto hits = device_hits(scene, rays);
  for (size_t i = 0; i < rays.size(); ++i) {
    const auto ref = reference_hit(scene, rays[i], 1e-6);
    ASSERT_EQ(hits[i].s[1], float(ref.second)) << "ray " << i;
    EXPECT_NEAR(hits[i].s[0], ref.first, 1e-5 * ref.first + 1e-5) << "ray " << i;
  }
}

// From hit points on every wall and ball, new Lambertian-distributed rays must not hit the
// surface they leave. docs/numerics.md measured 8-27% self-hits on the walls for tmin-only fixes of the
// textbook formula. The formula alone (skip = -1) leaves only grazing rays, whose near-zero root's
// error (about 1e-6 / cos(theta) on a wall) can exceed ray_epsilon: at most 1e-3 of the rays. With
// the sphere they leave named, as the renderer does, none.
TEST(SphereIntersect, NoSelfHitWhenLeavingWallsAndBalls) {
  const Scene scene = book_scene();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(-2.99, 8.99), y(0.01, 3.99), z(-2.99, 6.0);
  // First hits from the camera, computed on the device (float hit points, as in a render).
  std::vector<RayD> camera_rays;
  for (int i = 0; i < 40000; ++i)
    camera_rays.push_back({scene.camera.position, unit(subd({x(rng), y(rng), z(rng)}, scene.camera.position))});
  const auto first = device_hits(scene, camera_rays);
  std::vector<RayD> second;
  for (size_t i = 0; i < camera_rays.size(); ++i) {
    const int s = int(first[i].s[1]);
    if (s < 0 || s == 5) continue;  // missed, or the light
    const RayD& r = camera_rays[i];
    const float t = first[i].s[0];
    // The hit point exactly as the device forms it: camera-relative float o + t d.
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = double(float(t) * float(r.d[k])) + scene.camera.position[k];
    const Vec3 n = unit(subd(p, scene.spheres[s].center));
    second.push_back({p, random_cosine_direction(rng, n), s});
  }
  ASSERT_GT(second.size(), 30000u);
  std::vector<RayD> formula_only = second;
  for (RayD& r : formula_only) r.skip = -1;
  const auto with_skip = device_hits(scene, second);
  const auto without_skip = device_hits(scene, formula_only);
  int self_hits_formula = 0, self_hits_renderer = 0;
  for (size_t i = 0; i < second.size(); ++i) {
    self_hits_formula += int(without_skip[i].s[1]) == second[i].skip;
    self_hits_renderer += int(with_skip[i].s[1]) == second[i].skip;
  }
  EXPECT_LE(self_hits_formula, int(second.size() / 1000)) << "of " << second.size();
  EXPECT_EQ(self_hits_renderer, 0);
}

// At grazing angles the near-zero root's error exceeds any fixed epsilon; the renderer passes the
// sphere a ray leaves on its outer side, and then no grazing ray hits it again.
TEST(SphereIntersect, GrazingRaysSkipTheSphereTheyLeave) {
  const Scene scene = book_scene();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> px(-2.5, 8.5), pz(-2.5, 5.5), angle(0, 6.283185307179586);
  std::vector<RayD> rays;
  for (int i = 0; i < 5000; ++i) {
    // On the floor (y = 0), leaving at 1e-4..1e-2 rad above it.
    const double elevation = std::pow(10.0, -4.0 + 2.0 * (i % 100) / 100.0);
    const double a = angle(rng);
    const Vec3 d = unit({std::cos(a), std::tan(elevation), std::sin(a)});
    RayD r{{px(rng), 0.0, pz(rng)}, d, 0};
    rays.push_back(r);
  }
  const auto hits = device_hits(scene, rays);
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_NE(int(hits[i].s[1]), 0) << "ray " << i;
}

// Rays from inside the room towards the lines where two walls meet hit what the double-precision
// reference hits, or the other wall of that corner (the two distances agree to float rounding
// there): none leaks out of the room.
TEST(SphereIntersect, CornersDoNotLeak) {
  Scene scene = book_scene();
  scene.camera.position = {3.0, 2.0, 2.0};  // rays start at the device origin
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> along(-2.9, 8.9), jitter(-1e-3, 1e-3), height(0.1, 3.9),
      depth(-2.9, 6.0);
  std::vector<RayD> rays;
  std::vector<std::pair<int, int>> walls;
  const Vec3 from = scene.camera.position;
  for (int i = 0; i < 5000; ++i) {
    // floor/back wall edge (y=0, z=-3), left/back wall edge (x=-3, z=-3), right wall/ceiling (x=9, y=4)
    rays.push_back({from, unit(subd({along(rng), jitter(rng), -3.0 + jitter(rng)}, from))});
    walls.push_back({0, 4});
    rays.push_back({from, unit(subd({-3.0 + jitter(rng), height(rng), -3.0 + jitter(rng)}, from))});
    walls.push_back({2, 4});
    rays.push_back({from, unit(subd({9.0 + jitter(rng), 4.0 + jitter(rng), depth(rng)}, from))});
    walls.push_back({3, 1});
  }
  const auto hits = device_hits(scene, rays);
  for (size_t i = 0; i < rays.size(); ++i) {
    const int s = int(hits[i].s[1]);
    const int ref = reference_hit(scene, rays[i], 1e-6).second;
    const bool corner_wall = (s == walls[i].first || s == walls[i].second) &&
                             (ref == walls[i].first || ref == walls[i].second);
    EXPECT_TRUE(s == ref || corner_wall) << "ray " << i << " hit sphere " << s << ", reference " << ref;
  }
}

}  // namespace
}  // namespace clpt::test
