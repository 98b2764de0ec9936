// Semantic checks on a scene the loader has already checked for structure and types: every number
// finite and in range, inline meshes' indices in range, at least one emitter, a camera that
// defines a view. Messages name the dotted key and point at the value's position in the file
// (see SourceMap).
#include "scene/scene_validate.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "scene/pbr_params.h"
#include "scene/vec3_ops.h"
#include "util/error.h"

namespace clpt::scene_detail {

namespace {

// The last component of a dotted key ("sphere[2].material.ior" -> "ior"): messages say
// "ior must be ..." after the full key.
std::string leaf_name(const std::string& key) {
  const size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

// The enclosing key ("a.b" -> "a", "sphere[2]" -> "sphere", "sphere" -> "").
std::string parent_key(const std::string& key) {
  const size_t cut = key.find_last_of(".[");
  return cut == std::string::npos ? std::string() : key.substr(0, cut);
}

std::string format_vec3(const Vec3& v) {
  return "[" + format_number(v[0]) + ", " + format_number(v[1]) + ", " + format_number(v[2]) + "]";
}

bool all_finite(const Vec3& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}


// A rule violation on `key`, reported at the key's position.
[[noreturn]] void fail_at(const SourceMap& sources, const std::string& key,
                          const std::string& message) {
  fail(sources.find(key), key, message);
}

void require_finite(double value, const std::string& key, const SourceMap& sources) {
  if (!std::isfinite(value))
    fail_at(sources, key, leaf_name(key) + " must be finite (got " + format_number(value) + ")");
}

void require_finite(const Vec3& value, const std::string& key, const SourceMap& sources) {
  if (!all_finite(value))
    fail_at(sources, key, leaf_name(key) + " must be finite (got " + format_vec3(value) + ")");
}

// Closed interval [min, max]; NaN and infinities are reported as such first.
void require_in_range(double value, double min, double max, const std::string& key,
                      const SourceMap& sources) {
  require_finite(value, key, sources);
  if (value < min || value > max)
    fail_at(sources, key,
            leaf_name(key) + " must be in [" + format_number(min) + ", " + format_number(max) +
                "] (got " + format_number(value) + ")");
}

// Reflectance is an albedo per channel: a surface may not return more energy than it receives.
void check_reflectance(const Vec3& rho, const std::string& key, const SourceMap& sources) {
  require_finite(rho, key, sources);
  for (double channel : rho)
    if (channel < 0 || channel > 1)
      fail_at(sources, key, "reflectance must be in [0, 1] (got " + format_vec3(rho) + ")");
}

// A black emitter is allowed nowhere: it would count as "the scene's light" and render black.
void check_emission(const Vec3& emission, const std::string& key, const SourceMap& sources) {
  require_finite(emission, key, sources);
  for (double channel : emission)
    if (channel < 0)
      fail_at(sources, key, "emission must be >= 0 (got " + format_vec3(emission) + ")");
  if (emission[0] == 0 && emission[1] == 0 && emission[2] == 0)
    fail_at(sources, key, "emission must not be all zero (got " + format_vec3(emission) + ")");
}

// The Pbr parameters' ranges, as pbr_params.h declares them; emission may be 0 (a Pbr surface
// need not emit), and a volume's attenuation needs a thickness.
void check_pbr_material(const Material& m, const std::string& key, const SourceMap& sources) {
  for (const PbrNumber& n : kPbrNumbers) {
    const std::string k = key + "." + n.key;
    if (n.max == kPbrUnbounded) {
      require_finite(m.*n.field, k, sources);
      if (m.*n.field < n.min)
        fail_at(sources, k, leaf_name(k) + " must be >= " + format_number(n.min) + " (got " + format_number(m.*n.field) + ")");
    } else {
      require_in_range(m.*n.field, n.min, n.max, k, sources);
    }
  }
  for (const PbrColour& c : kPbrColours) {
    const std::string k = key + "." + c.key;
    const Vec3& v = m.*c.field;
    require_finite(v, k, sources);
    for (double channel : v)
      if (channel < 0 || (c.max_one && channel > 1))
        fail_at(sources, k, leaf_name(k) + (c.max_one ? " must be in [0, 1]" : " must be >= 0") + " (got " +
                                format_vec3(v) + ")");
  }
}

// Only the parameters of the material's own type are checked: the loader leaves the others at
// their defaults (it rejects keys that do not apply to the type).
void check_material(const Material& m, const std::string& key, const SourceMap& sources) {
  switch (m.type) {
    case MaterialType::Pbr:
      check_pbr_material(m, key, sources);
      break;
    case MaterialType::Lambertian:
    case MaterialType::Mirror:
      check_reflectance(m.reflectance, key + ".reflectance", sources);
      break;
    case MaterialType::Phong:
      check_reflectance(m.reflectance, key + ".reflectance", sources);
      require_in_range(m.phong_exponent, 0, 1e6, key + ".exponent", sources);
      break;
    case MaterialType::Glass:
      check_reflectance(m.reflectance, key + ".reflectance", sources);
      require_in_range(m.ior, 1, 10, key + ".ior", sources);
      break;
    case MaterialType::Emitter:
      check_emission(m.emission, key + ".emission", sources);
      break;
  }
}

void check_sphere(const Sphere& sphere, const std::string& key, const SourceMap& sources) {
  require_finite(sphere.center, key + ".center", sources);
  require_finite(sphere.radius, key + ".radius", sources);
  if (!(sphere.radius > 0))
    fail_at(sources, key + ".radius",
            "radius must be > 0 (got " + format_number(sphere.radius) + ")");
  check_material(sphere.material, key + ".material", sources);
}

// An index row of an inline mesh: every index in [0, vertex_count).
template <size_t N>
void check_indices(const std::array<int64_t, N>& row, size_t vertex_count, const std::string& key,
                   const SourceMap& sources) {
  for (int64_t index : row)
    if (index < 0 || uint64_t(index) >= vertex_count)
      fail_at(sources, key,
              "index " + std::to_string(index) + " is out of range (the mesh has " + std::to_string(vertex_count) +
                  " vertices, indices 0 to " + std::to_string(int64_t(vertex_count) - 1) + ")");
}

template <size_t N>
std::array<uint32_t, 3> corners(const std::array<int64_t, N>& row, size_t a, size_t b, size_t c) {
  return {uint32_t(row[a]), uint32_t(row[b]), uint32_t(row[c])};
}

// A punctual light: finite position, a direction that is not zero, an intensity >= 0 and not all
// zero, a range >= 0 (0: none), spot cones 0 <= inner < outer <= 90 degrees.
void check_light(const PunctualLight& light, const std::string& key, const SourceMap& sources) {
  require_finite(light.position, key + ".position", sources);
  require_finite(light.direction, key + ".direction", sources);
  if (light.type != LightType::Point && length(light.direction) == 0)
    fail_at(sources, key + ".direction", "direction must not be the zero vector");
  const std::string strength = key + ".intensity";  // candela/lux: the table's position stands in
  require_finite(light.intensity, strength, sources);
  for (double channel : light.intensity)
    if (channel < 0) fail_at(sources, strength, "intensity must be >= 0 (got " + format_vec3(light.intensity) + ")");
  if (light.intensity[0] == 0 && light.intensity[1] == 0 && light.intensity[2] == 0)
    fail_at(sources, strength, "intensity must not be all zero (got " + format_vec3(light.intensity) + ")");
  require_finite(light.range, key + ".range", sources);
  if (light.range < 0) fail_at(sources, key + ".range", "range must be >= 0 (got " + format_number(light.range) + ")");
  if (light.type != LightType::Spot) return;
  require_in_range(degrees_of(light.inner_cone_rad), 0, 90, key + ".inner_cone_deg", sources);
  require_in_range(degrees_of(light.outer_cone_rad), 0, 90, key + ".outer_cone_deg", sources);
  if (!(light.inner_cone_rad < light.outer_cone_rad))
    fail_at(sources, key + ".inner_cone_deg",
            "inner_cone_deg must be below outer_cone_deg (got " + format_number(degrees_of(light.inner_cone_rad)) +
                " and " + format_number(degrees_of(light.outer_cone_rad)) + ")");
}

// The camera must define a view direction, and `up` must pick a roll around it.
void check_camera(const Camera& camera, const SourceMap& sources) {
  require_finite(camera.position, "camera.position", sources);
  require_finite(camera.look_at, "camera.look_at", sources);
  require_finite(camera.up, "camera.up", sources);
  if (camera.projection == Projection::Orthographic) {
    require_finite(camera.ortho_height, "camera.height", sources);
    if (!(camera.ortho_height > 0))
      fail_at(sources, "camera.height", "height must be > 0 (got " + format_number(camera.ortho_height) + ")");
  }
  require_finite(camera.vertical_fov_deg, "camera.vertical_fov_deg", sources);
  if (!(camera.vertical_fov_deg > 0 && camera.vertical_fov_deg < 180))
    fail_at(sources, "camera.vertical_fov_deg",
            "vertical_fov_deg must be in (0, 180) (got " + format_number(camera.vertical_fov_deg) +
                ")");
  const Vec3 view = sub(camera.look_at, camera.position);
  // Relative test: a look_at one rounding step away from a far position gives no direction.
  const double scale = std::max(length(camera.position), length(camera.look_at));
  if (length(view) <= 1e-9 * scale || length(view) == 0)
    fail_at(
        sources, "camera.look_at",
        "look_at must differ from camera.position (both are " + format_vec3(camera.look_at) + ")");
  if (length(camera.up) == 0) fail_at(sources, "camera.up", "up must not be the zero vector");
  const double sine = length(cross(view, camera.up)) / (length(view) * length(camera.up));
  if (sine < 1e-6)
    fail_at(sources, "camera.up",
            "up must not be parallel to the view direction (got " + format_vec3(camera.up) +
                ", view direction " + format_vec3(view) + ")");
}

}  // namespace

void check_mesh_placement(const MeshPlacement& placement, const std::string& key, const SourceMap& sources) {
  require_finite(placement.scale, key + ".scale", sources);
  for (double s : placement.scale)
    if (!(s > 0)) fail_at(sources, key + ".scale", "scale must be > 0 (got " + format_vec3(placement.scale) + ")");
  require_finite(placement.rotate_deg, key + ".rotate_deg", sources);
  require_finite(placement.translate, key + ".translate", sources);
}

LocalMesh inline_local_mesh(const InlineMeshRows& rows, const std::string& key, const SourceMap& sources) {
  const auto row_key = [&](const char* array, size_t i) { return key + "." + array + "[" + std::to_string(i) + "]"; };
  if (rows.vertices.empty()) fail_at(sources, key + ".vertices", "the mesh has no vertices");
  if (rows.vertices.size() > std::numeric_limits<uint32_t>::max())
    fail_at(sources, key + ".vertices", "more than 2^32 - 1 vertices");
  LocalMesh mesh;
  for (size_t i = 0; i < rows.vertices.size(); ++i) {
    require_finite(rows.vertices[i], row_key("vertices", i), sources);
    mesh.positions.push_back(rows.vertices[i]);
  }
  if (!rows.normals.empty() && rows.normals.size() != rows.vertices.size())
    fail_at(sources, key + ".normals",
            "normals must have one entry per vertex (got " + std::to_string(rows.normals.size()) + " for " +
                std::to_string(rows.vertices.size()) + " vertices)");
  for (size_t i = 0; i < rows.normals.size(); ++i) {
    const Vec3& n = rows.normals[i];
    require_finite(n, row_key("normals", i), sources);
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) fail_at(sources, row_key("normals", i), "a normal must not be zero");
    mesh.normals.push_back(n);
  }
  if (!rows.uvs.empty() && rows.uvs.size() != rows.vertices.size())
    fail_at(sources, key + ".uvs",
            "uvs must have one entry per vertex (got " + std::to_string(rows.uvs.size()) + " for " +
                std::to_string(rows.vertices.size()) + " vertices)");
  for (size_t i = 0; i < rows.uvs.size(); ++i) {
    if (!std::isfinite(rows.uvs[i][0]) || !std::isfinite(rows.uvs[i][1]))
      fail_at(sources, row_key("uvs", i), "texture coordinates must be finite");
    mesh.uvs.push_back(rows.uvs[i]);
  }
  if (rows.triangles.empty() && rows.quads.empty())
    fail_at(sources, key, "the mesh has neither triangles nor quads");
  for (size_t i = 0; i < rows.triangles.size(); ++i) {
    check_indices(rows.triangles[i], rows.vertices.size(), row_key("triangles", i), sources);
    mesh.triangles.push_back(corners(rows.triangles[i], 0, 1, 2));
  }
  for (size_t i = 0; i < rows.quads.size(); ++i) {
    check_indices(rows.quads[i], rows.vertices.size(), row_key("quads", i), sources);
    mesh.triangles.push_back(corners(rows.quads[i], 0, 1, 2));
    mesh.triangles.push_back(corners(rows.quads[i], 0, 2, 3));
  }
  return mesh;
}

void check_placed_mesh(const TriangleMesh& mesh, size_t dropped, const std::string& key, const SourceMap& sources) {
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (!all_finite(mesh.positions[i]))
      fail_at(sources, key + ".scale",
              "vertex " + std::to_string(i) + " is not finite after scale, rotate_deg and translate (got " +
                  format_vec3(mesh.positions[i]) + ")");
  if (mesh.triangles.empty())
    fail_at(sources, key,
            "the mesh has no triangles left: all " + std::to_string(dropped) + " have zero area after placement");
}

namespace {

void check_settings(const RenderSettings& settings, const SourceMap& sources) {
  // The grid sampler places spp / 16 samples at each of 4 x 4 sub-pixel positions.
  if (settings.sampler == Sampler::Grid && settings.spp % 16 != 0)
    fail_at(sources, "render.spp",
            "the grid sampler needs spp to be a multiple of 16 (got " +
                std::to_string(settings.spp) + ")");
  if (settings.estimator != "book" && settings.estimator != "nee")
    fail_at(sources, "render.estimator",
            "unknown estimator '" + settings.estimator + "' (expected 'book' or 'nee')");
  if (settings.light_sampling != "cap" && settings.light_sampling != "sphere")
    fail_at(sources, "render.light_sampling",
            "unknown light sampling '" + settings.light_sampling + "' (expected 'cap' or 'sphere')");
}

// Light comes from an emitter, a Pbr material with an emission, a punctual light or the environment.
void require_emitter(const Scene& scene, const SourceMap& sources) {
  const auto emits = [](const Material& m) {
    return m.type == MaterialType::Emitter ||
           (m.type == MaterialType::Pbr && (m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0));
  };
  if (!scene.lights.empty() || scene.environment) return;
  for (const Sphere& sphere : scene.spheres)
    if (emits(sphere.material)) return;
  for (const TriangleMesh& mesh : scene.meshes)
    if (emits(mesh.material)) return;
  fail(SourcePosition{sources.file(), 1, 1}, scene.spheres.empty() ? "mesh" : "sphere",
       "the scene has no emitter or light, so every image would be black");
}

struct IntegerRule {
  const char* key;
  int64_t min;
  int64_t max;
};

constexpr int64_t kNoLimit = std::numeric_limits<int64_t>::max();
constexpr IntegerRule kIntegerRules[] = {
    {"image.width", 1, 16384},    {"image.height", 1, 16384},      {"render.spp", 1, 1000000000},
    {"render.seed", 0, kNoLimit}, {"render.max_bounces", 0, 1000}, {"render.rr_from", 0, 1000},
};

}  // namespace

void SourceMap::record(const std::string& key, const SourcePosition& where) {
  positions_[key] = {where.line, where.column};
}

SourcePosition SourceMap::find(const std::string& key) const {
  for (std::string k = key; !k.empty(); k = parent_key(k)) {
    const auto it = positions_.find(k);
    if (it != positions_.end()) return SourcePosition{file_, it->second.first, it->second.second};
  }
  return SourcePosition{file_, 1, 1};
}

void fail(const SourcePosition& where, const std::string& key, const std::string& message) {
  throw Error(ExitCode::BadScene, where.str() + ": " + key + ": " + message);
}

std::string format_number(double value) {
  // Integral values print without exponent up to 2^53 ("100000", not to_chars' "1e+05").
  if (std::isfinite(value) && value == std::trunc(value) && std::fabs(value) < 9.007199254740992e15)
    return std::to_string(static_cast<int64_t>(value));
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

void check_integer_setting(const std::string& key, int64_t value, const SourcePosition& where) {
  for (const IntegerRule& rule : kIntegerRules) {
    if (key != rule.key) continue;
    if (value >= rule.min && value <= rule.max) return;
    const std::string range = rule.max == kNoLimit ? " must be >= " + std::to_string(rule.min)
                                                   : " must be in [" + std::to_string(rule.min) +
                                                         ", " + std::to_string(rule.max) + "]";
    fail(where, key, leaf_name(key) + range + " (got " + std::to_string(value) + ")");
  }
  throw std::logic_error("check_integer_setting: no rule for '" + key + "'");
}

void validate_scene(const Scene& scene, const SourceMap& sources) {
  check_settings(scene.settings, sources);
  check_camera(scene.camera, sources);
  for (size_t i = 0; i < scene.spheres.size(); ++i)
    check_sphere(scene.spheres[i], "sphere[" + std::to_string(i) + "]", sources);
  for (size_t i = 0; i < scene.meshes.size(); ++i)
    check_material(scene.meshes[i].material, "mesh[" + std::to_string(i) + "].material", sources);
  for (size_t i = 0; i < scene.lights.size(); ++i) check_light(scene.lights[i], "light[" + std::to_string(i) + "]", sources);
  require_emitter(scene, sources);
}

double degrees_of(double radians) {
  return std::round(radians * (180 / 3.14159265358979323846) * 1e9) / 1e9;
}

}  // namespace clpt::scene_detail
