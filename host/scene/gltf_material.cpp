// glTF materials -> Material (gltf_material.h).
#include "scene/gltf_material.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include "scene/gltf_document.h"
#include "scene/gltf_error.h"
#include "scene/texture_load.h"

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

// The images already loaded, by (image index, colour space): one decode per image and use.
struct ImageCache {
  const tinygltf::Model& model;
  const std::string& path;
  std::vector<TextureImage>& images;
  std::map<std::pair<int, ColorSpace>, int> loaded;
};

std::string extension_for(const std::string& mime, const std::string& uri) {
  if (mime == "image/png") return ".png";
  if (mime == "image/jpeg") return ".jpg";
  const size_t dot = uri.rfind('.');
  if (!uri.empty() && dot != std::string::npos && uri.find('/', dot) == std::string::npos && uri.size() - dot <= 6)
    return uri.substr(dot);
  return ".png";
}

// Image `index` in colour space `space`, loaded once; `element` names the referring texture.
int load_image(ImageCache& cache, int index, ColorSpace space, const std::string& element) {
  if (const auto it = cache.loaded.find({index, space}); it != cache.loaded.end()) return it->second;
  const tinygltf::Image& image = cache.model.images[size_t(index)];
  const std::string image_element = "images[" + std::to_string(index) + "]";
  const std::string what = cache.path + ": " + element + " (" + image_element + ")";
  int loaded;
  if (!image.uri.empty()) {
    // An external file: a relative path inside the glTF file's folder, as buffers' URIs are.
    const std::string name = gltf_decode_uri(image.uri, image_element + ".uri");
    gltf_check_relative(name, image_element + ".uri");
    const std::string file = (std::filesystem::path(cache.path).parent_path() / name).string();
    loaded = load_texture_image(cache.images, file, file, space, what);
  } else {
    // The GLB's buffer view or a data: URI: tinygltf handed over the encoded bytes (gltf_document.cpp).
    if (image.image.empty()) gltf_fail(image_element, "the image has no bytes");
    const std::string_view bytes(reinterpret_cast<const char*>(image.image.data()), image.image.size());
    loaded = load_texture_image_bytes(cache.images, bytes, extension_for(image.mimeType, image.uri),
                                      cache.path + ": " + image_element, space, what);
  }
  cache.loaded[{index, space}] = loaded;
  return loaded;
}

TextureWrap wrap_of(int mode, const std::string& element) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::Clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::Mirror;
  }
  gltf_fail(element, std::to_string(mode) + " is not a wrap mode (10497, 33071 or 33648)");
}

// KHR_texture_transform's offset, rotation and scale, conjugated into clpt's coordinates (OBJ's:
// v' = 1 - v of glTF's; scene.h): M = F T R S F with F(u, v) = (u, 1 - v).
std::array<double, 6> texture_transform(const tinygltf::ExtensionMap& extensions, const std::string& element) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end()) return {1, 0, 0, 0, 1, 0};
  const std::string e = element + ".extensions.KHR_texture_transform";
  if (!it->second.IsObject()) gltf_fail(e, "must be an object");
  const tinygltf::Value& t = it->second;
  const auto pair = [&](const char* key, double fallback, std::array<double, 2>& out) {
    out = {fallback, fallback};
    if (!t.Has(key)) return;
    const tinygltf::Value& v = t.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
      gltf_fail(e + "." + key, "must be an array of 2 numbers");
    out = {v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble()};
    if (!std::isfinite(out[0]) || !std::isfinite(out[1])) gltf_fail(e + "." + key, "must be finite");
  };
  std::array<double, 2> offset, scale;
  pair("offset", 0, offset);
  pair("scale", 1, scale);
  const double rotation = ext_number(t, "rotation", 0, -1e6, 1e6, e);
  const double c = std::cos(rotation), s = std::sin(rotation);
  // glTF: u' = a u + b v + ox, v' = d u + e v + oy (the extension's T R S).
  const double a = scale[0] * c, b = scale[1] * s, d = -scale[0] * s, ee = scale[1] * c;
  return {a, -b, b + offset[0], -d, ee, 1 - ee - offset[1]};
}

// The coordinate set a texture reads: KHR_texture_transform's texCoord where it has one (it
// overrides the textureInfo's, as the extension says), else `tex_coord`; at most kMaxUvSet.
int tex_coord_of(int tex_coord, const tinygltf::ExtensionMap& extensions, const std::string& element) {
  int set = tex_coord;
  std::string where = element + ".texCoord";
  if (const auto it = extensions.find("KHR_texture_transform"); it != extensions.end() && it->second.IsObject() &&
                                                                 it->second.Has("texCoord")) {
    where = element + ".extensions.KHR_texture_transform.texCoord";
    const tinygltf::Value& v = it->second.Get("texCoord");
    if (!v.IsInt()) gltf_fail(where, "must be an integer");
    set = v.GetNumberAsInt();
  }
  if (set < 0 || set > kMaxUvSet)
    gltf_fail(where, std::to_string(set) + " is not a coordinate set clpt reads (TEXCOORD_0 to TEXCOORD_" +
                         std::to_string(kMaxUvSet) + ")");
  return set;
}

// The texture `info` (a textureInfo or normalTextureInfo: index, texCoord, extensions) as a
// TextureRef, its image loaded in colour space `space`; `ref_set` gets its coordinate set.
TextureRef texture_ref(ImageCache& cache, int index, int tex_coord, const tinygltf::ExtensionMap& extensions,
                       ColorSpace space, const std::string& element, int& ref_set) {
  TextureRef ref;
  if (index < 0) return ref;
  const tinygltf::Model& model = cache.model;
  if (size_t(index) >= model.textures.size())
    gltf_fail(element + ".index", std::to_string(index) + " is out of range (the file has " +
                                      std::to_string(model.textures.size()) + " textures)");
  ref_set = tex_coord_of(tex_coord, extensions, element);
  const tinygltf::Texture& texture = model.textures[size_t(index)];
  const std::string t = "textures[" + std::to_string(index) + "]";
  if (texture.source < 0) gltf_fail(t + ".source", "missing (clpt reads no texture extensions' image sources)");
  if (size_t(texture.source) >= model.images.size())
    gltf_fail(t + ".source", std::to_string(texture.source) + " is out of range (the file has " +
                                 std::to_string(model.images.size()) + " images)");
  if (texture.sampler >= 0) {
    if (size_t(texture.sampler) >= model.samplers.size())
      gltf_fail(t + ".sampler", std::to_string(texture.sampler) + " is out of range (the file has " +
                                    std::to_string(model.samplers.size()) + " samplers)");
    const tinygltf::Sampler& sampler = model.samplers[size_t(texture.sampler)];
    const std::string s = "samplers[" + std::to_string(texture.sampler) + "]";
    ref.wrap_u = wrap_of(sampler.wrapS, s + ".wrapS");
    ref.wrap_v = wrap_of(sampler.wrapT, s + ".wrapT");
    // Magnification decides: clpt reads no mipmaps (docs/textures.md).
    if (sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) ref.filter = TextureFilter::Nearest;
  }
  ref.uv_transform = texture_transform(extensions, element);
  ref.where = cache.path + ": " + element + ".index";
  ref.image = load_image(cache, texture.source, space, element);
  return ref;
}

void read_textures(ImageCache& cache, const tinygltf::Material& m, const std::string& element, Material& out,
                   std::vector<std::string>& warnings) {
  const auto& pbr = m.pbrMetallicRoughness;
  const std::string p = element + ".pbrMetallicRoughness.";
  MaterialTextures& t = out.textures;
  // Each texture's coordinate set (-1: no texture); the material's is the base colour's, else the
  // first texture's in this order.
  int sets[4] = {-1, -1, -1, -1};
  const std::string names[4] = {p + "baseColorTexture", p + "metallicRoughnessTexture", element + ".emissiveTexture",
                                element + ".normalTexture"};
  t.base_color = texture_ref(cache, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                             pbr.baseColorTexture.extensions, ColorSpace::Srgb, names[0], sets[0]);
  // Roughness in G, metalness in B (linear).
  const auto& mr = pbr.metallicRoughnessTexture;
  t.roughness = texture_ref(cache, mr.index, mr.texCoord, mr.extensions, ColorSpace::Linear, names[1], sets[1]);
  t.metallic = t.roughness;
  t.roughness.channel = 1;
  t.metallic.channel = 2;
  t.emission = texture_ref(cache, m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions,
                           ColorSpace::Srgb, names[2], sets[2]);
  t.normal = texture_ref(cache, m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions,
                         ColorSpace::Linear, names[3], sets[3]);
  int chosen = -1;
  for (int i = 0; i < 4 && chosen < 0; ++i) chosen = sets[i] >= 0 ? i : -1;
  if (chosen >= 0) {
    t.uv_set = sets[chosen];
    for (int i = 0; i < 4; ++i)
      if (sets[i] >= 0 && sets[i] != t.uv_set)
        warnings.push_back(names[i] + ".texCoord: " + std::to_string(sets[i]) + ", but " + names[chosen] +
                           " reads TEXCOORD_" + std::to_string(t.uv_set) + "; clpt gives a material one coordinate set, so this texture reads TEXCOORD_" +
                           std::to_string(t.uv_set) + " too");
  }
  t.normal_scale = m.normalTexture.scale;
  if (!std::isfinite(t.normal_scale) || std::fabs(t.normal_scale) > 100)
    gltf_fail(element + ".normalTexture.scale", "must be a number in [-100, 100]");
  if (m.occlusionTexture.index >= 0 && size_t(m.occlusionTexture.index) >= cache.model.textures.size())
    gltf_fail(element + ".occlusionTexture.index", std::to_string(m.occlusionTexture.index) + " is out of range (the file has " +
                                                       std::to_string(cache.model.textures.size()) + " textures)");
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
  // Alpha (docs/gltf.md, "Alpha"): baseColorFactor's alpha, times the base colour texture's alpha
  // channel on the device; OPAQUE ignores it, as the specification says.
  out.textures.alpha_mode = m.alphaMode == "MASK" ? AlphaMode::Mask : m.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
  out.textures.alpha = pbr.baseColorFactor[3];
  out.textures.alpha_cutoff = m.alphaCutoff;
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

std::vector<Material> convert_materials(const tinygltf::Model& model, const std::string& path,
                                        std::vector<TextureImage>& images, std::vector<std::string>& warnings) {
  std::vector<Material> out;
  std::vector<std::string> occluded;
  ImageCache cache{model, path, images, {}};
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const std::string element = "materials[" + std::to_string(i) + "]";
    const tinygltf::Material& m = model.materials[i];
    out.push_back(convert(m, element));
    read_textures(cache, m, element, out.back(), warnings);
    if (m.occlusionTexture.index >= 0) occluded.push_back(element);
  }
  if (!occluded.empty())
    warnings.push_back(joined(occluded) + ": occlusionTexture ignored (a path tracer finds occlusion itself)");
  return out;
}

}  // namespace clpt
