// glTF materials -> Material (gltf_material.h).
#include "scene/gltf_material.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "scene/gltf_error.h"

namespace clpt {
namespace {

// Six significant digits, as a message shows a value ("1.5", "inf").
std::string shown(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void require_in(double value, double min, double max, const std::string& element) {
  if (!std::isfinite(value) || value < min || value > max)
    gltf_fail(element, "must be in [" + shown(min) + ", " + shown(max) + "] (got " + shown(value) + ")");
}

Vec3 colour(const std::vector<double>& values, size_t length, const std::string& element) {
  if (values.size() != length)
    gltf_fail(element, "must have " + std::to_string(length) + " numbers (got " + std::to_string(values.size()) + ")");
  for (size_t i = 0; i < values.size(); ++i) require_in(values[i], 0, 1, element + "[" + std::to_string(i) + "]");
  return {values[0], values[1], values[2]};
}

// The number `key` of the extension object `ext`, else `fallback`; in [min, max].
double ext_number(const tinygltf::Value& ext, const char* key, double fallback, double min, double max,
                  const std::string& element) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsNumber()) gltf_fail(element + "." + key, "must be a number");
  const double value = v.GetNumberAsDouble();
  require_in(value, min, max, element + "." + key);
  return value;
}

Vec3 ext_colour(const tinygltf::Value& ext, const char* key, const std::string& element) {
  if (!ext.Has(key)) return {1, 1, 1};
  const tinygltf::Value& v = ext.Get(key);
  std::vector<double> values;
  if (v.IsArray())
    for (size_t i = 0; i < v.ArrayLen() && i < 4; ++i) {
      if (!v.Get(int(i)).IsNumber()) gltf_fail(element + "." + key, "must be an array of 3 numbers");
      values.push_back(v.Get(int(i)).GetNumberAsDouble());
    }
  if (!v.IsArray() || v.ArrayLen() != 3) gltf_fail(element + "." + key, "must be an array of 3 numbers");
  return colour(values, 3, element + "." + key);
}

// The extension `name` of material `m`, if it has it (an object).
const tinygltf::Value* extension(const tinygltf::Material& m, const char* name, const std::string& element) {
  const auto it = m.extensions.find(name);
  if (it == m.extensions.end()) return nullptr;
  if (!it->second.IsObject()) gltf_fail(element + ".extensions." + name, "must be an object");
  return &it->second;
}

void check_texture(int index, const tinygltf::Model& model, const std::string& element, bool& used) {
  if (index < 0) return;
  if (size_t(index) >= model.textures.size())
    gltf_fail(element + ".index", std::to_string(index) + " is out of range (the file has " +
                                      std::to_string(model.textures.size()) + " textures)");
  used = true;
}

// Textures are not read yet; their indices are checked and their use reported.
bool uses_textures(const tinygltf::Material& m, const tinygltf::Model& model, const std::string& element) {
  bool used = false;
  check_texture(m.pbrMetallicRoughness.baseColorTexture.index, model, element + ".pbrMetallicRoughness.baseColorTexture", used);
  check_texture(m.pbrMetallicRoughness.metallicRoughnessTexture.index, model,
                element + ".pbrMetallicRoughness.metallicRoughnessTexture", used);
  check_texture(m.normalTexture.index, model, element + ".normalTexture", used);
  check_texture(m.occlusionTexture.index, model, element + ".occlusionTexture", used);
  check_texture(m.emissiveTexture.index, model, element + ".emissiveTexture", used);
  return used;
}

void read_extensions(const tinygltf::Material& m, const std::string& element, Material& out) {
  const std::string ext = element + ".extensions.";
  double strength = 1;
  if (const auto* e = extension(m, "KHR_materials_emissive_strength", element))
    strength = ext_number(*e, "emissiveStrength", 1, 0, std::numeric_limits<double>::infinity(),
                          ext + "KHR_materials_emissive_strength");
  out.emission = {out.emission[0] * strength, out.emission[1] * strength, out.emission[2] * strength};
  // KHR_materials_ior allows ior = 0 (a mirror-like limit); clpt's dielectric takes [1, 10] as TOML glass does.
  if (const auto* e = extension(m, "KHR_materials_ior", element))
    out.ior = ext_number(*e, "ior", 1.5, 1, 10, ext + "KHR_materials_ior");
  if (const auto* e = extension(m, "KHR_materials_transmission", element))
    out.transmission = ext_number(*e, "transmissionFactor", 0, 0, 1, ext + "KHR_materials_transmission");
  if (const auto* e = extension(m, "KHR_materials_volume", element)) {
    const std::string v = ext + "KHR_materials_volume";
    out.thickness = ext_number(*e, "thicknessFactor", 0, 0, std::numeric_limits<double>::infinity(), v);
    out.attenuation_color = ext_colour(*e, "attenuationColor", v);
    const double distance = ext_number(*e, "attenuationDistance", std::numeric_limits<double>::infinity(), 0,
                                       std::numeric_limits<double>::infinity(), v);
    if (e->Has("attenuationDistance") && !(distance > 0)) gltf_fail(v + ".attenuationDistance", "must be > 0");
    out.attenuation_distance = std::isinf(distance) ? 0 : distance;
  }
}

Material convert(const tinygltf::Material& m, const std::string& element) {
  Material out;
  out.type = MaterialType::Pbr;
  const auto& pbr = m.pbrMetallicRoughness;
  out.reflectance = colour(pbr.baseColorFactor, 4, element + ".pbrMetallicRoughness.baseColorFactor");
  require_in(pbr.metallicFactor, 0, 1, element + ".pbrMetallicRoughness.metallicFactor");
  require_in(pbr.roughnessFactor, 0, 1, element + ".pbrMetallicRoughness.roughnessFactor");
  out.metallic = pbr.metallicFactor;
  out.roughness = pbr.roughnessFactor;
  out.emission = colour(m.emissiveFactor, 3, element + ".emissiveFactor");
  if (m.alphaMode != "OPAQUE" && m.alphaMode != "MASK" && m.alphaMode != "BLEND")
    gltf_fail(element + ".alphaMode", "'" + m.alphaMode + "' (expected OPAQUE, MASK or BLEND)");
  require_in(m.alphaCutoff, 0, std::numeric_limits<double>::infinity(), element + ".alphaCutoff");
  out.double_sided = m.doubleSided;
  read_extensions(m, element, out);
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < 8; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > 8) out += " and " + std::to_string(names.size() - 8) + " more";
  return out;
}

}  // namespace

std::vector<Material> convert_materials(const tinygltf::Model& model, std::vector<std::string>& warnings) {
  std::vector<Material> out;
  std::vector<std::string> textured, transparent;
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const std::string element = "materials[" + std::to_string(i) + "]";
    const tinygltf::Material& m = model.materials[i];
    out.push_back(convert(m, element));
    if (uses_textures(m, model, element)) textured.push_back(element);
    if (m.alphaMode != "OPAQUE") transparent.push_back(element);
  }
  if (!textured.empty())
    warnings.push_back(joined(textured) + ": textures are not read yet; their factors alone are rendered");
  if (!transparent.empty())
    warnings.push_back(joined(transparent) + ": alphaMode MASK and BLEND are not rendered yet; these surfaces render opaque");
  return out;
}

}  // namespace clpt
