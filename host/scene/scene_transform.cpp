// Similarity transforms of a whole scene (scene_transform.h): spheres, meshes, punctual lights and
// the camera.
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
  // A mesh's world positions scale with the scene; its placement composes: factor * (M p + t)
  // = (factor M) p + factor t, so a file mesh is written back as the same file (scene_writer).
  for (TriangleMesh& m : out.meshes) {
    for (Vec3& p : m.positions) p = scale(p, factor);
    m.placement.scale = scale(m.placement.scale, factor);
    m.placement.translate = scale(m.placement.translate, factor);
  }
  // A point or spot light's irradiance I / d^2 at the scaled distances is kept by I factor^2 (an
  // emitter's radiance needs no change); a directional light's needs none.
  for (PunctualLight& l : out.lights) {
    l.position = scale(l.position, factor);
    l.range *= factor;
    if (l.type != LightType::Directional) l.intensity = scale(l.intensity, factor * factor);
  }
  const auto scale_volume = [factor](Material& m) {
    m.thickness *= factor;
    m.attenuation_distance *= factor;
  };
  for (Sphere& s : out.spheres) scale_volume(s.material);
  for (TriangleMesh& m : out.meshes) scale_volume(m.material);
  out.camera.position = scale(out.camera.position, factor);
  out.camera.look_at = scale(out.camera.look_at, factor);
  out.camera.ortho_height *= factor;
  return out;
}

Scene translate_scene(const Scene& scene, const Vec3& offset) {
  for (double o : offset)
    if (!std::isfinite(o)) throw std::invalid_argument("translation must be finite");
  Scene out = scene;
  for (Sphere& s : out.spheres) s.center = add(s.center, offset);
  for (TriangleMesh& m : out.meshes) {
    for (Vec3& p : m.positions) p = add(p, offset);
    m.placement.translate = add(m.placement.translate, offset);
  }
  for (PunctualLight& l : out.lights) l.position = add(l.position, offset);
  out.camera.position = add(out.camera.position, offset);
  out.camera.look_at = add(out.camera.look_at, offset);
  return out;
}

Scene scale_emission(const Scene& scene, double factor) {
  require_positive_finite(factor, "emission factor");
  Scene out = scene;
  for (Sphere& s : out.spheres)
    if (s.material.type == MaterialType::Emitter) s.material.emission = scale(s.material.emission, factor);
  for (TriangleMesh& m : out.meshes)
    if (m.material.type == MaterialType::Emitter || m.material.type == MaterialType::Pbr)
      m.material.emission = scale(m.material.emission, factor);
  for (PunctualLight& l : out.lights) l.intensity = scale(l.intensity, factor);
  return out;
}

}  // namespace clpt
