#include "scene/device_scene.h"

#include <cmath>

#include "scene/vec3_ops.h"
#include "util/error.h"

namespace clpt {
namespace {

void store(float out[3], const Vec3& v) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<float>(v[i]);
}
// v as a float and the float of what that float left out (types.h: the *_lo fields).
float store_split(double v, float& lo) {
  const float hi = static_cast<float>(v);
  lo = static_cast<float>(v - double(hi));
  return hi;
}
void store_split(float hi[3], float lo[3], const Vec3& v) {
  for (int i = 0; i < 3; ++i) hi[i] = store_split(v[i], lo[i]);
}

GpuSphere to_gpu(const Sphere& s, const Vec3& anchor, const Vec3& camera_position) {
  GpuSphere g{};
  const SurfaceFrame frame = surface_frame(s, anchor);
  store_split(g.surface_point, g.surface_point_lo, sub(frame.point, camera_position));
  store_split(g.surface_normal, g.surface_normal_lo, frame.normal);
  g.radius = store_split(s.radius, g.radius_lo);
  g.material = static_cast<clpt_u32>(s.material.type);
  store(g.reflectance, s.material.reflectance);
  g.phong_exponent = static_cast<float>(s.material.phong_exponent);
  store(g.emission, s.material.emission);
  g.ior = static_cast<float>(s.material.ior);
  return g;
}

}  // namespace

SurfaceFrame surface_frame(const Sphere& s, const Vec3& anchor) {
  const Vec3 towards_anchor = sub(anchor, s.center);
  // A sphere centred on the anchor has no closest point: any direction will do.
  const Vec3 n0 = length(towards_anchor) > 0 ? normalize(towards_anchor) : Vec3{0, 1, 0};
  return {add(s.center, scale(n0, s.radius)), n0};
}

LightSampling light_sampling_of(const RenderSettings& settings) {
  return settings.light_sampling == "sphere" ? LightSampling::Sphere : LightSampling::Cap;
}

std::vector<GpuLight> light_caps(const Scene& scene) {
  const LightSampling sampling = light_sampling_of(scene.settings);
  const double pi = 3.14159265358979323846;
  std::vector<GpuLight> lights;
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& a = scene.spheres[i];
    if (a.material.type != MaterialType::Emitter) continue;
    double one_minus_cos = 2;      // the whole sphere
    Vec3 axis = {0, 1, 0};
    bool hidden = false;
    for (size_t j = 0; j < scene.spheres.size() && sampling == LightSampling::Cap; ++j) {
      const Sphere& b = scene.spheres[j];
      if (j == i) continue;
      const Vec3 offset = sub(a.center, b.center);
      const double d = length(offset);
      if (d + a.radius <= b.radius) {  // a lies inside b: never seen
        hidden = true;
        break;
      }
      if (d >= a.radius + b.radius || d + b.radius <= a.radius) continue;  // b does not cut a
      // Points of a at angle theta from the axis (from b's centre through a's) are outside b when
      // 1 - cos(theta) < ((d + ra)^2 - rb^2) / (2 d ra), factored so that the walls' 1e5 radii
      // do not cancel: (d + ra - rb)(d + ra + rb) / (2 d ra).
      const double cut = (d + a.radius - b.radius) * (d + a.radius + b.radius) / (2 * d * a.radius);
      if (cut < one_minus_cos) {
        one_minus_cos = cut;
        axis = scale(offset, 1.0 / d);
      }
    }
    if (hidden || one_minus_cos <= 0) continue;
    GpuLight light{};
    store(light.cap_axis, axis);
    light.sphere = static_cast<clpt_u32>(i);
    light.one_minus_cos_cap = static_cast<float>(one_minus_cos);
    light.cap_area = static_cast<float>(2 * pi * a.radius * a.radius * one_minus_cos);
    lights.push_back(light);
  }
  return lights;
}

double ray_epsilon_for(const Camera& camera, Precision precision) {
  // Float: 1e-5 of the view distance, measured on the book's scene (docs/numerics.md). Double rounds
  // 2^29 times finer, so its epsilon is that much smaller: otherwise a ball far away, with the
  // look-at point on it, would skip hits closer than 1e-5 of its distance, i.e. its own interior.
  const double scale = precision == Precision::Double ? 0x1p-29 : 1.0;
  return 1e-5 * scale * length(sub(camera.look_at, camera.position));
}

DeviceScene make_device_scene(const Scene& scene, int width, int height, Precision precision) {
  // Issue 14 part A loads meshes; part B (branch bvh) uploads and traverses them and replaces
  // this refusal, the one place that stands between a loaded mesh and the device.
  if (!scene.meshes.empty())
    throw Error(ExitCode::BadScene, scene.meshes[0].where.str() + ": mesh[0]: meshes are not rendered yet");
  DeviceScene out;
  const Camera& cam = scene.camera;
  for (const Sphere& s : scene.spheres) out.spheres.push_back(to_gpu(s, cam.look_at, cam.position));
  out.lights = light_caps(scene);

  // The book's sensor, scaled to unit distance: only directions matter for a pinhole.
  const Vec3 dir = normalize(sub(cam.look_at, cam.position));
  const double pi = 3.14159265358979323846;
  const double sensor_height = 2.0 * std::tan(cam.vertical_fov_deg * pi / 360.0);
  const double sensor_width = sensor_height * width / height;
  const Vec3 right = scale(normalize(cross(dir, cam.up)), sensor_width);
  const Vec3 up = scale(normalize(cross(right, dir)), sensor_height);
  store(out.camera.sensor_center, dir);
  store(out.camera.sensor_right, right);
  store(out.camera.sensor_up, up);
  out.ray_epsilon = static_cast<float>(ray_epsilon_for(cam, precision));
  return out;
}

}  // namespace clpt
