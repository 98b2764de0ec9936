#include "scene/scene_writer.h"

#include <toml++/toml.h>

#include <sstream>

#include "util/atomic_file.h"

namespace clpt {
namespace {

toml::array vec3_array(const Vec3& v) { return toml::array{v[0], v[1], v[2]}; }

toml::table material_table(const Material& m) {
  toml::table t{{"type", material_type_name(m.type)}};
  switch (m.type) {
    case MaterialType::Lambertian:
    case MaterialType::Mirror:
      t.insert("reflectance", vec3_array(m.reflectance));
      break;
    case MaterialType::Phong:
      t.insert("reflectance", vec3_array(m.reflectance));
      t.insert("exponent", m.phong_exponent);
      break;
    case MaterialType::Glass:
      t.insert("reflectance", vec3_array(m.reflectance));
      t.insert("ior", m.ior);
      break;
    case MaterialType::Emitter:
      t.insert("emission", vec3_array(m.emission));
      break;
  }
  t.is_inline(true);  // `material = { ... }`, as the README writes it
  return t;
}

toml::table sphere_table(const Sphere& s) {
  toml::table t{{"name", s.name}, {"center", vec3_array(s.center)}, {"radius", s.radius}};
  t.insert("material", material_table(s.material));
  return t;
}

}  // namespace

std::string scene_to_toml(const Scene& scene, const std::string& header) {
  const RenderSettings& r = scene.settings;
  const Camera& c = scene.camera;
  toml::table root;
  root.insert("image", toml::table{{"width", r.width}, {"height", r.height}});
  root.insert("render", toml::table{{"spp", r.spp},
                                    {"seed", static_cast<int64_t>(r.seed)},
                                    {"max_bounces", r.max_bounces},
                                    {"sampler", sampler_name(r.sampler)},
                                    {"estimator", r.estimator}});
  root.insert("camera", toml::table{{"position", vec3_array(c.position)},
                                    {"look_at", vec3_array(c.look_at)},
                                    {"up", vec3_array(c.up)},
                                    {"vertical_fov_deg", c.vertical_fov_deg}});
  toml::array spheres;
  for (const Sphere& s : scene.spheres) spheres.push_back(sphere_table(s));
  root.insert("sphere", std::move(spheres));

  std::ostringstream out;
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  if (!header.empty()) out << "\n";
  out << root << "\n";
  return out.str();
}

void write_scene_file(const std::string& path, const Scene& scene, const std::string& header) {
  write_file_atomically(path, scene_to_toml(scene, header), "scene");
}

}  // namespace clpt
