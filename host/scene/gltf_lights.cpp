// KHR_lights_punctual -> PunctualLight (gltf_lights.h). Read from the extension's JSON (as
// tinygltf keeps it) rather than tinygltf's Light, which cannot tell a range of 0 from none.
#include "scene/gltf_lights.h"

#include <cmath>

#include "scene/gltf_error.h"
#include "scene/vec3_ops.h"

namespace clpt {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLumensPerWatt = 683;
constexpr const char* kExtension = "KHR_lights_punctual";

double number(const tinygltf::Value& object, const char* key, double fallback, const std::string& element) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) gltf_fail(element + "." + key, "must be a finite number");
  return v.GetNumberAsDouble();
}

Vec3 light_colour(const tinygltf::Value& light, const std::string& element) {
  if (!light.Has("color")) return {1, 1, 1};
  const tinygltf::Value& v = light.Get("color");
  if (!v.IsArray() || v.ArrayLen() != 3) gltf_fail(element + ".color", "must be an array of 3 numbers");
  Vec3 out{};
  for (int i = 0; i < 3; ++i) {
    const tinygltf::Value& c = v.Get(i);
    if (!c.IsNumber() || !(c.GetNumberAsDouble() >= 0 && c.GetNumberAsDouble() <= 1))
      gltf_fail(element + ".color[" + std::to_string(i) + "]", "must be in [0, 1]");
    out[size_t(i)] = c.GetNumberAsDouble();
  }
  return out;
}

// lights[index] of the extension, checked, with position and direction still to set.
PunctualLight read_light(const tinygltf::Value& light, size_t index) {
  const std::string element = std::string(kExtension) + ".lights[" + std::to_string(index) + "]";
  if (!light.IsObject()) gltf_fail(element, "must be an object");
  PunctualLight out;
  out.name = light.Has("name") && light.Get("name").IsString() ? light.Get("name").Get<std::string>()
                                                               : "lights[" + std::to_string(index) + "]";
  const std::string type = light.Has("type") && light.Get("type").IsString() ? light.Get("type").Get<std::string>() : "";
  if (type == "point") out.type = LightType::Point;
  else if (type == "spot") out.type = LightType::Spot;
  else if (type == "directional") out.type = LightType::Directional;
  else gltf_fail(element + ".type", "'" + type + "' (expected point, spot or directional)");
  const double intensity = number(light, "intensity", 1, element);
  if (intensity < 0) gltf_fail(element + ".intensity", "must be >= 0 (got " + std::to_string(intensity) + ")");
  out.intensity = scale(light_colour(light, element), intensity / kLumensPerWatt);
  if (light.Has("range")) {
    out.range = number(light, "range", 0, element);
    if (!(out.range > 0)) gltf_fail(element + ".range", "must be > 0 (got " + std::to_string(out.range) + ")");
  }
  if (out.type == LightType::Spot) {
    // tinygltf has refused a spot light without its `spot` object; it drops an empty one ({}:
    // all defaults) from the Value it keeps, so a missing one here means the defaults.
    static const tinygltf::Value kNoProperties;
    const tinygltf::Value& spot = light.Has("spot") ? light.Get("spot") : kNoProperties;
    if (light.Has("spot") && !spot.IsObject()) gltf_fail(element + ".spot", "must be an object");
    out.inner_cone_rad = number(spot, "innerConeAngle", 0, element + ".spot");
    out.outer_cone_rad = number(spot, "outerConeAngle", kPi / 4, element + ".spot");
    if (!(out.inner_cone_rad >= 0 && out.inner_cone_rad < out.outer_cone_rad && out.outer_cone_rad <= kPi / 2))
      gltf_fail(element + ".spot", "the cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2 (got " +
                                       std::to_string(out.inner_cone_rad) + " and " + std::to_string(out.outer_cone_rad) + ")");
  }
  return out;
}

std::vector<PunctualLight> file_lights(const tinygltf::Model& model) {
  std::vector<PunctualLight> out;
  const auto it = model.extensions.find(kExtension);
  if (it == model.extensions.end()) return out;
  if (!it->second.IsObject() || !it->second.Has("lights") || !it->second.Get("lights").IsArray())
    gltf_fail(std::string("extensions.") + kExtension, "must be an object with a 'lights' array");
  const tinygltf::Value& lights = it->second.Get("lights");
  for (size_t i = 0; i < lights.ArrayLen(); ++i) out.push_back(read_light(lights.Get(int(i)), i));
  return out;
}

// The light index a node's KHR_lights_punctual extension names, or -1.
int node_light(const tinygltf::Model& model, int node, size_t light_count) {
  const auto& extensions = model.nodes[size_t(node)].extensions;
  const auto it = extensions.find(kExtension);
  if (it == extensions.end()) return -1;
  const std::string element = "nodes[" + std::to_string(node) + "].extensions." + kExtension + ".light";
  if (!it->second.IsObject() || !it->second.Has("light") || !it->second.Get("light").IsInt())
    gltf_fail(element, "must be an integer");
  const int light = it->second.Get("light").GetNumberAsInt();
  if (light < 0 || size_t(light) >= light_count)
    gltf_fail(element, std::to_string(light) + " is out of range (the file has " + std::to_string(light_count) + " lights)");
  return light;
}

}  // namespace

std::vector<PunctualLight> convert_lights(const tinygltf::Model& model, const std::vector<NodeInstance>& nodes,
                                          double range_scale, const std::string& file) {
  const std::vector<PunctualLight> lights = file_lights(model);
  std::vector<PunctualLight> out;
  for (const NodeInstance& instance : nodes) {
    const int index = node_light(model, instance.node, lights.size());
    if (index < 0) continue;
    PunctualLight light = lights[size_t(index)];
    light.position = instance.world.translation;
    light.direction = normalize(transform_vector(instance.world, {0, 0, -1}));
    light.range *= range_scale;
    light.where = SourcePosition{file, 0, 0};
    out.push_back(std::move(light));
  }
  return out;
}

}  // namespace clpt
