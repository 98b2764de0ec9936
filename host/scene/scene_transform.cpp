#include "scene/scene_transform.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace clpt {
namespace {

void require_positive_finite(double value, const char* what) {
  if (!(value > 0) || !std::isfinite(value))
    throw std::invalid_argument(std::string(what) + " must be > 0 and finite (got " +
                                std::to_string(value) + ")");
}

Vec3 scaled(const Vec3& v, double factor) { return {v[0] * factor, v[1] * factor, v[2] * factor}; }
Vec3 shifted(const Vec3& v, const Vec3& offset) { return {v[0] + offset[0], v[1] + offset[1], v[2] + offset[2]}; }

}  // namespace

Scene scale_scene(const Scene& scene, double factor) {
  require_positive_finite(factor, "scale factor");
  Scene out = scene;
  for (Sphere& s : out.spheres) {
    s.center = scaled(s.center, factor);
    s.radius *= factor;
  }
  out.camera.position = scaled(out.camera.position, factor);
  out.camera.look_at = scaled(out.camera.look_at, factor);
  return out;
}

Scene translate_scene(const Scene& scene, const Vec3& offset) {
  for (double o : offset)
    if (!std::isfinite(o)) throw std::invalid_argument("translation must be finite");
  Scene out = scene;
  for (Sphere& s : out.spheres) s.center = shifted(s.center, offset);
  out.camera.position = shifted(out.camera.position, offset);
  out.camera.look_at = shifted(out.camera.look_at, offset);
  return out;
}

Scene scale_emission(const Scene& scene, double factor) {
  require_positive_finite(factor, "emission factor");
  Scene out = scene;
  for (Sphere& s : out.spheres)
    if (s.material.type == MaterialType::Emitter) s.material.emission = scaled(s.material.emission, factor);
  return out;
}

}  // namespace clpt
