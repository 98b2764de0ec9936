// Textures as the scene holds them: plain data. A TextureImage is a decoded image with the
// storage its texels will have on the device (8-bit, half or float; 1 to 4 channels) and its
// colour space; a TextureRef is one use of an image by a material parameter (which image, its
// wrap and filter modes, its uv transform, the channel a scalar reads). The loaders (TOML:
// scene_loader.cpp; glTF: gltf_material.cpp) fill them; device_textures.cpp packs them for the
// kernels (kernels/texture.cl). Conventions: docs/textures.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace clpt {

// Values equal the kernels' CLPT_TEXEL_*, CLPT_WRAP_* (kernels/types.h).
enum class TexelStorage : uint32_t { U8 = 0, Half = 1, Float = 2 };
enum class TextureWrap : uint32_t { Repeat = 0, Clamp = 1, Mirror = 2 };
enum class TextureFilter : uint32_t { Bilinear = 0, Nearest = 1 };
enum class ColorSpace : uint32_t { Srgb = 0, Linear = 1 };
// glTF alphaMode; values equal CLPT_ALPHA_* (kernels/types.h, kernels/alpha.cl).
enum class AlphaMode : uint32_t { Opaque = 0, Mask = 1, Blend = 2 };

const char* texel_storage_name(TexelStorage storage);  // "8-bit", "half", "float"
const char* texture_wrap_name(TextureWrap wrap);       // "repeat", "clamp", "mirror"
const char* texture_filter_name(TextureFilter filter); // "bilinear", "nearest"
const char* color_space_name(ColorSpace space);        // "srgb", "linear"

// Bytes one texel channel takes on the device.
uint32_t texel_bytes(TexelStorage storage);

// A decoded image as the device will hold it. Row 0 is the image's top row. `pixels` holds
// width * height * channels values as decoded (8-bit and 16-bit samples as value / max): for
// storage U8 with colour space sRGB they are still sRGB-encoded (the device decodes each texel
// before filtering, so 8 bits keep their precision in the darks); half and float storage hold
// linear values (an sRGB image stored as half or float is linearised when it is loaded).
struct TextureImage {
  std::string file;  // the file as the scene names it, or "FILE.glb: images[N]" for an embedded one
  std::string hash;  // FNV-1a 64 of the encoded bytes, hex (chained into the scene's hash)
  int width = 0;
  int height = 0;
  int channels = 0;  // 1 to 4
  TexelStorage storage = TexelStorage::U8;
  ColorSpace color_space = ColorSpace::Srgb;
  std::vector<float> pixels;
  uint64_t device_bytes() const { return uint64_t(width) * uint64_t(height) * uint64_t(channels) * texel_bytes(storage); }
};

// One material parameter's texture. The parameter's value (factor) multiplies what the lookup
// returns. uv_transform maps the mesh's texture coordinates (OBJ's convention, (0, 0) at the
// image's bottom-left: TriangleMesh::uvs) to the coordinates the image is read at, in the same
// convention: u' = t[0] u + t[1] v + t[2], v' = t[3] u + t[4] v + t[5].
struct TextureRef {
  int image = -1;  // index into Scene::images; -1: the parameter is not textured
  TextureWrap wrap_u = TextureWrap::Repeat;
  TextureWrap wrap_v = TextureWrap::Repeat;
  TextureFilter filter = TextureFilter::Bilinear;
  std::array<double, 6> uv_transform{1, 0, 0, 0, 1, 0};
  int channel = 0;    // the channel a scalar parameter reads (0 to 3); colours read RGB
  std::string where;  // the key or element that named it, for messages ("scene.toml:4:3: mesh[0].material.reflectance")
  bool used() const { return image >= 0; }
};

// The textured parameters of a material (Material::textures). Colours multiply their factor per
// channel (base colour: the reflectance; emission); scalars multiply theirs (metallic and
// roughness). `normal`: a tangent-space normal map (docs/textures.md), its xy scaled by normal_scale.
struct MaterialTextures {
  TextureRef base_color;
  TextureRef metallic;
  TextureRef roughness;
  TextureRef emission;
  TextureRef normal;
  double normal_scale = 1;
  // The texture coordinate set every texture of the material reads: glTF's texCoord (TEXCOORD_n;
  // gltf_material.cpp picks one per material), 0 elsewhere. A mesh carries that one set (its uvs).
  int uv_set = 0;
  // glTF alphaMode (docs/gltf.md, "Alpha"): the alpha is `alpha` (baseColorFactor[3]) x the base
  // colour texture's alpha channel (1 without one). MASK: the surface is there where alpha >=
  // alpha_cutoff; BLEND: there with probability alpha (coverage); OPAQUE ignores alpha. Carried
  // to the device in the texturing buffer (a MASK or BLEND material has a record there).
  AlphaMode alpha_mode = AlphaMode::Opaque;
  double alpha = 1;
  double alpha_cutoff = 0.5;
  bool any() const { return base_color.used() || metallic.used() || roughness.used() || emission.used() || normal.used(); }
};

// The colour space a file's pixels default to: sRGB for 8-bit samples (PNG, JPEG), linear for
// everything else (16-bit, half, float: EXR, HDR, float TIFF).
ColorSpace default_color_space(const std::string& pixel_type);

// The device storage for a file's sample type: 8-bit for 8-bit samples, half for 16-bit and half
// samples, float otherwise.
TexelStorage storage_for(const std::string& pixel_type);

// An image no larger than this in either dimension, and with at most kMaxTexturePixels pixels,
// is accepted (larger ones are refused before they are packed).
constexpr int kMaxTextureDimension = 32768;
constexpr uint64_t kMaxTexturePixels = uint64_t(1) << 28;

// sRGB's decoding curve (IEC 61966-2-1), in double: what the device's lookups are checked against.
double srgb_to_linear(double encoded);

// The texture lookup done on the host in double, as kernels/texture.cl does it in float: image
// `image` read through `ref`'s wrap modes, filter and uv transform at the mesh coordinates (u, v),
// sRGB decoded per texel before filtering; returns RGBA (1 channel: grey, alpha 1; 2: grey and
// alpha; 3: alpha 1). The texels are the stored ones (8-bit values rounded as the device holds them).
std::array<double, 4> lookup_texture_on_host(const TextureImage& image, const TextureRef& ref, double u, double v);

// A sphere's texture coordinates at the unit outward normal (x, y, z) = (p - c) / r, the spherical
// mapping (docs/textures.md; kernels/texture.cl, sphere_uv, in float): u = 1/2 - atan2(x, -z) /
// (2 pi), v = 1 - acos(y) / pi. Blender's sphere projection in clpt's +Y-up world: the image's centre
// faces -Z, its top row is the north pole +Y.
std::array<double, 2> sphere_texture_coordinates(double x, double y, double z);

// The texel value the device holds for a decoded sample (8-bit: rounded to 1/255; half: rounded
// to half; float: as is).
double stored_texel(TexelStorage storage, float value);

}  // namespace clpt
