#include "scene/scene_transform.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/vec3_ops.h"

namespace clpt {
namespace {

void require_positive_finite(double value, const char* what) {
  if (!(value > 0) || !std::isfinite(value))
    throw std::invalid_argument(std::string(what) + " must be > 0 and finite (got " +
                                std::to_string(value) + ")");
}


}  // namespace

Scene scale_scene(const Scene& scene, double factor) {
  require_positive_finite(factor, "scale factor");
  Scene out = scene;
  for (Sphere& s : out.spheres) {
    s.center = scale(s.center, factor);
    s.radius *= factor;
  }
  out.camera.position = scale(out.camera.position, factor);
  out.camera.look_at = scale(out.camera.look_at, factor);
  return out;
}

Scene translate_scene(const Scene& scene, const Vec3& offset) {
  for (double o : offset)
    if (!std::isfinite(o)) throw std::invalid_argument("translation must be finite");
  Scene out = scene;
  for (Sphere& s : out.spheres) s.center = add(s.center, offset);
  out.camera.position = add(out.camera.position, offset);
  out.camera.look_at = add(out.camera.look_at, offset);
  return out;
}

Scene scale_emission(const Scene& scene, double factor) {
  require_positive_finite(factor, "emission factor");
  Scene out = scene;
  for (Sphere& s : out.spheres)
    if (s.material.type == MaterialType::Emitter) s.material.emission = scale(s.material.emission, factor);
  return out;
}

}  // namespace clpt
