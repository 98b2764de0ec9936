// Texture names, defaults and the host's reference lookup (texture.h).
#include "scene/texture.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "util/half_float.h"

namespace clpt {

const char* texel_storage_name(TexelStorage storage) {
  switch (storage) {
    case TexelStorage::U8: return "8-bit";
    case TexelStorage::Half: return "half";
    default: return "float";
  }
}

const char* texture_wrap_name(TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::Clamp: return "clamp";
    case TextureWrap::Mirror: return "mirror";
    default: return "repeat";
  }
}

const char* texture_filter_name(TextureFilter filter) {
  return filter == TextureFilter::Nearest ? "nearest" : "bilinear";
}

const char* color_space_name(ColorSpace space) { return space == ColorSpace::Linear ? "linear" : "srgb"; }

uint32_t texel_bytes(TexelStorage storage) {
  return storage == TexelStorage::U8 ? 1u : storage == TexelStorage::Half ? 2u : 4u;
}

ColorSpace default_color_space(const std::string& pixel_type) {
  return pixel_type == "uint8" || pixel_type == "int8" ? ColorSpace::Srgb : ColorSpace::Linear;
}

TexelStorage storage_for(const std::string& pixel_type) {
  if (pixel_type == "uint8" || pixel_type == "int8") return TexelStorage::U8;
  if (pixel_type == "uint16" || pixel_type == "int16" || pixel_type == "half") return TexelStorage::Half;
  return TexelStorage::Float;
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double stored_texel(TexelStorage storage, float value) {
  switch (storage) {
    case TexelStorage::U8: return std::round(std::clamp(double(value), 0.0, 1.0) * 255.0) / 255.0;
    case TexelStorage::Half: return half_bits_to_float(float_to_half_bits(value));
    default: return value;
  }
}

namespace {

// Wraps the coordinate s (in image widths) into the range the mode reads: [0, 1) for repeat,
// [0, 2) for mirror (one period), [-1, 2] for clamp (the texels beyond are the edge's anyway).
double reduce(double s, TextureWrap wrap) {
  if (wrap == TextureWrap::Repeat) return s - std::floor(s);
  if (wrap == TextureWrap::Mirror) return s - 2 * std::floor(s / 2);
  return std::clamp(s, -1.0, 2.0);
}

int wrap_index(int i, int n, TextureWrap wrap) {
  if (wrap == TextureWrap::Clamp) return std::clamp(i, 0, n - 1);
  if (wrap == TextureWrap::Repeat) return ((i % n) + n) % n;
  const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
  return m < n ? m : 2 * n - 1 - m;
}

std::array<double, 4> texel(const TextureImage& image, int x, int y) {
  const size_t at = (size_t(y) * size_t(image.width) + size_t(x)) * size_t(image.channels);
  double c[4] = {0, 0, 0, 1};
  for (int k = 0; k < image.channels; ++k) c[k] = stored_texel(image.storage, image.pixels[at + k]);
  const bool srgb = image.storage == TexelStorage::U8 && image.color_space == ColorSpace::Srgb;
  const auto decode = [&](double value) { return srgb ? srgb_to_linear(value) : value; };
  switch (image.channels) {
    case 1: return {decode(c[0]), decode(c[0]), decode(c[0]), 1};
    case 2: return {decode(c[0]), decode(c[0]), decode(c[0]), c[1]};
    case 3: return {decode(c[0]), decode(c[1]), decode(c[2]), 1};
    default: return {decode(c[0]), decode(c[1]), decode(c[2]), c[3]};
  }
}

}  // namespace

std::array<double, 2> sphere_texture_coordinates(double x, double y, double z) {
  const double pi = 3.14159265358979323846;
  return {0.5 - std::atan2(x, -z) / (2 * pi), 1 - std::acos(std::clamp(y, -1.0, 1.0)) / pi};
}

std::array<double, 4> lookup_texture_on_host(const TextureImage& image, const TextureRef& ref, double u, double v) {
  const auto& t = ref.uv_transform;
  const double tu = t[0] * u + t[1] * v + t[2];
  const double tv = t[3] * u + t[4] * v + t[5];
  // Image coordinates: x from the left, y from the top, in texels (texel centres at i + 0.5).
  const double x = reduce(tu, ref.wrap_u) * image.width;
  const double y = (1 - reduce(tv, ref.wrap_v)) * image.height;
  if (ref.filter == TextureFilter::Nearest) {
    const int ix = wrap_index(int(std::floor(x)), image.width, ref.wrap_u);
    const int iy = wrap_index(int(std::floor(y)), image.height, ref.wrap_v);
    return texel(image, ix, iy);
  }
  const double fx = x - 0.5, fy = y - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const double wx = fx - x0, wy = fy - y0;
  const int ix0 = wrap_index(int(x0), image.width, ref.wrap_u), ix1 = wrap_index(int(x0) + 1, image.width, ref.wrap_u);
  const int iy0 = wrap_index(int(y0), image.height, ref.wrap_v), iy1 = wrap_index(int(y0) + 1, image.height, ref.wrap_v);
  const auto a = texel(image, ix0, iy0), b = texel(image, ix1, iy0), c = texel(image, ix0, iy1), d = texel(image, ix1, iy1);
  std::array<double, 4> out{};
  for (int k = 0; k < 4; ++k) out[k] = (1 - wy) * ((1 - wx) * a[k] + wx * b[k]) + wy * ((1 - wx) * c[k] + wx * d[k]);
  return out;
}

}  // namespace clpt
