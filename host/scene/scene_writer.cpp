// Scene -> TOML (scene_writer.h): spheres, meshes (file or inline), punctual lights, the camera
// and the settings.
#include "scene/scene_writer.h"

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <sstream>
#include <system_error>
#include <vector>

#include "scene/mesh_file.h"
#include "scene/pbr_params.h"
#include "scene/scene_validate.h"

#include "util/atomic_file.h"
#include "util/error.h"

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
    case MaterialType::Pbr:
      for (const PbrColour& c : kPbrColours) t.insert(c.key, vec3_array(m.*c.field));
      for (const PbrNumber& n : kPbrNumbers) t.insert(n.key, m.*n.field);
      t.insert(kPbrDoubleSidedKey, m.double_sided);
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

toml::array rows_array(const std::vector<Vec3>& rows) {
  toml::array out;
  for (const Vec3& row : rows) out.push_back(vec3_array(row));
  return out;
}

toml::array rows_array(const std::vector<std::array<uint32_t, 3>>& rows) {
  toml::array out;
  for (const auto& t : rows) out.push_back(toml::array{int64_t(t[0]), int64_t(t[1]), int64_t(t[2])});
  return out;
}

// The mesh file `m.file` of the scene `scene_file`, named for a scene file at `written_as`.
std::string mesh_file_for(const std::string& scene_file, const TriangleMesh& m, const std::string& written_as) {
  namespace fs = std::filesystem;
  const fs::path target = fs::absolute(resolve_mesh_path(scene_file, m.file));
  std::error_code ec;
  const fs::path relative = fs::relative(target, fs::absolute(directory_of(written_as)), ec);
  return ec || relative.empty() ? target.string() : relative.generic_string();
}

toml::table mesh_table(const TriangleMesh& m, const std::string& scene_file, const std::string& written_as) {
  toml::table t{{"name", m.name}};
  if (!m.file.empty()) {
    t.insert("file", mesh_file_for(scene_file, m, written_as));
    t.insert("scale", vec3_array(m.placement.scale));
    t.insert("rotate_deg", vec3_array(m.placement.rotate_deg));
    t.insert("translate", vec3_array(m.placement.translate));
  } else {
    t.insert("vertices", rows_array(m.positions));
    if (!m.normals.empty()) t.insert("normals", rows_array(m.normals));
    t.insert("triangles", rows_array(m.triangles));
  }
  t.insert("material", material_table(m.material));
  return t;
}

// glTF content cannot be written back yet (scene_writer.h). A glTF light carries no line in
// `where` (TOML positions always do).
void refuse_gltf_content(const Scene& scene) {
  std::string source;
  for (const TriangleMesh& m : scene.meshes)
    if (!m.gltf_element.empty()) source = m.file;
  for (const PunctualLight& l : scene.lights)
    if (l.where.line == 0) source = l.where.file;
  if (!source.empty())
    throw Error(ExitCode::Usage, scene.file + ": the scene holds glTF content (from " + source +
                                     "), which clpt cannot write back as a TOML scene yet");
  // Texture tables are not written back yet either (docs/textures.md).
  if (!scene.images.empty())
    throw Error(ExitCode::Usage, scene.file + ": the scene has textures (" + scene.images.front().file +
                                     "), which clpt cannot write back as a TOML scene yet");
}

// A punctual light as [[light]] writes it, its strength radiometric (`intensity`, W/sr or W/m^2).
toml::table light_table(const PunctualLight& l) {
  toml::table t{{"name", l.name}, {"type", light_type_name(l.type)}};
  if (l.type != LightType::Directional) t.insert("position", vec3_array(l.position));
  if (l.type != LightType::Point) t.insert("direction", vec3_array(l.direction));
  t.insert("intensity", vec3_array(l.intensity));
  if (l.type != LightType::Directional && l.range > 0) t.insert("range", l.range);
  if (l.type == LightType::Spot) {
    t.insert("inner_cone_deg", scene_detail::degrees_of(l.inner_cone_rad));
    t.insert("outer_cone_deg", scene_detail::degrees_of(l.outer_cone_rad));
  }
  return t;
}

toml::table camera_table(const Camera& c) {
  toml::table t{{"position", vec3_array(c.position)}, {"look_at", vec3_array(c.look_at)}, {"up", vec3_array(c.up)}};
  if (c.projection == Projection::Orthographic) {
    t.insert("projection", "orthographic");
    t.insert("height", c.ortho_height);
  } else {
    t.insert("vertical_fov_deg", c.vertical_fov_deg);
  }
  return t;
}

}  // namespace

std::string scene_to_toml(const Scene& scene, const std::string& header, const std::string& written_as) {
  refuse_gltf_content(scene);
  const RenderSettings& r = scene.settings;
  const Camera& c = scene.camera;
  toml::table root;
  root.insert("image", toml::table{{"width", r.width}, {"height", r.height}});
  root.insert("render", toml::table{{"spp", r.spp},
                                    {"seed", static_cast<int64_t>(r.seed)},
                                    {"max_bounces", r.max_bounces},
                                    {"sampler", sampler_name(r.sampler)},
                                    {"estimator", r.estimator}});
  root.insert("camera", camera_table(c));
  toml::array spheres;
  for (const Sphere& s : scene.spheres) spheres.push_back(sphere_table(s));
  if (!spheres.empty()) root.insert("sphere", std::move(spheres));
  toml::array meshes;
  for (const TriangleMesh& m : scene.meshes) meshes.push_back(mesh_table(m, scene.file, written_as));
  if (!meshes.empty()) root.insert("mesh", std::move(meshes));
  toml::array lights;
  for (const PunctualLight& l : scene.lights) lights.push_back(light_table(l));
  if (!lights.empty()) root.insert("light", std::move(lights));

  std::ostringstream out;
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  if (!header.empty()) out << "\n";
  out << root << "\n";
  return out.str();
}

void write_scene_file(const std::string& path, const Scene& scene, const std::string& header) {
  write_file_atomically(path, scene_to_toml(scene, header, path), "scene");
}

}  // namespace clpt
