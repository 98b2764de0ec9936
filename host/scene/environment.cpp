#include "scene/environment.h"

#include <cmath>
#include <filesystem>
#include <system_error>

#include "scene/gltf_loader.h"
#include "scene/scene_image.h"
#include "util/hash.h"

namespace clpt {
namespace {

std::string number_text(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

// sRGB's decoding to linear (IEC 61966-2-1), for 8- and 16-bit files.
float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : static_cast<float>(std::pow((double(c) + 0.055) / 1.055, 2.4));
}

}  // namespace

void load_environment_image(Environment& env, const std::string& path, ExitCode code) {
  const std::string prefix = env.what + ": " + env.file + ": ";
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw Error(code, prefix + "no such file");
  if (std::filesystem::is_directory(status)) throw Error(code, prefix + "is a directory, not an image");
  const uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes == 0) throw Error(code, prefix + "the file is empty (0 bytes)");
  SceneImagePixels image;
  try {
    image = read_scene_image(path, env.what);
  } catch (const Error& e) {
    throw Error(code, e.what());
  }
  const uint64_t texels = uint64_t(image.width) * uint64_t(image.height);
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
    throw Error(code, prefix + "the image has no pixels");
  if (texels > kMaxEnvironmentTexels)
    throw Error(code, prefix + "the image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                          " texels; at most " + std::to_string(kMaxEnvironmentTexels) +
                          " (2^26, e.g. 8192 x 8192) are supported");
  auto rgb = std::make_shared<std::vector<float>>(texels * 3);
  const int channels = image.channels;
  const bool srgb = image.pixel_type == "uint8" || image.pixel_type == "uint16";
  // Lossy compression (EXR's DWAA/DWAB, as Blender's own studio lights use) leaves a few texels
  // slightly negative: read as 0, as Cycles and pbrt do, and said once. NaN and infinity are errors.
  uint64_t negative = 0;
  float most_negative = 0;
  uint64_t most_negative_texel = 0;
  for (uint64_t t = 0; t < texels; ++t) {
    const float* p = &image.pixels[t * channels];
    float c[3] = {p[0], channels >= 3 ? p[1] : p[0], channels >= 3 ? p[2] : p[0]};
    bool clamped = false;
    for (float& v : c) {
      if (!std::isfinite(v))
        throw Error(code, prefix + "texel (" + std::to_string(t % image.width) + ", " +
                              std::to_string(t / image.width) + ") has the value " + number_text(v) +
                              " (radiance must be finite)");
      if (v < 0) {
        if (v < most_negative) most_negative = v, most_negative_texel = t;
        v = 0, clamped = true;
      }
    }
    negative += clamped ? 1 : 0;
    for (int k = 0; k < 3; ++k) (*rgb)[3 * t + k] = srgb ? srgb_to_linear(c[k]) : c[k];
  }
  env.notice.clear();
  if (negative > 0) {
    char most[32];
    std::snprintf(most, sizeof most, "%.3g", double(most_negative));
    env.notice = prefix + std::to_string(negative) + " texel" + (negative == 1 ? " is" : "s are") +
                 " negative (the most negative " + most + " at (" +
                 std::to_string(most_negative_texel % image.width) + ", " +
                 std::to_string(most_negative_texel / image.width) + "), as lossy compression leaves them); read as 0";
  }
  env.width = image.width;
  env.height = image.height;
  env.hash = hex64(fnv1a64(std::string_view(reinterpret_cast<const char*>(rgb->data()), rgb->size() * sizeof(float))));
  env.rgb = std::move(rgb);
}

Environment default_environment() {
  Environment env;
  env.file = "";
  env.what = "clpt's default studio environment";
  env.width = kDefaultEnvironmentWidth;
  env.height = kDefaultEnvironmentHeight;
  auto rgb = std::make_shared<std::vector<float>>(size_t(kDefaultEnvironmentWidth) * kDefaultEnvironmentHeight * 3);
  constexpr double kPi = 3.14159265358979323846;
  for (int row = 0; row < kDefaultEnvironmentHeight; ++row) {
    // The row's centre: theta = pi (row + 0.5) / height from the zenith (environment.cl's mapping).
    const double y = std::cos(kPi * (row + 0.5) / kDefaultEnvironmentHeight);
    const float radiance = float(0.25 + 0.75 * (1 + y) / 2);
    for (int column = 0; column < kDefaultEnvironmentWidth; ++column)
      for (int c = 0; c < 3; ++c) (*rgb)[3 * (size_t(row) * kDefaultEnvironmentWidth + column) + c] = radiance;
  }
  env.hash = hex64(fnv1a64(std::string_view(reinterpret_cast<const char*>(rgb->data()), rgb->size() * sizeof(float))));
  env.rgb = std::move(rgb);
  return env;
}

std::string light_unlit_scene(Scene& scene) {
  if (unlit_scene_warning(scene).empty()) return "";
  scene.environment = default_environment();
  chain_environment_hash(scene);
  return scene.file + ": the scene has no lights, no emissive material and no environment; lit by clpt's default "
                      "studio environment (white, 1 at the zenith to 0.25 at the nadir; --environment FILE to light it "
                      "otherwise, --environment none to render it black)";
}

void chain_environment_hash(Scene& scene) {
  if (!scene.environment) return;
  const Environment& e = *scene.environment;
  const std::string text = "environment\n" + e.file + '\0' + e.hash + '\0' + number_text(e.color[0]) + ' ' +
                           number_text(e.color[1]) + ' ' + number_text(e.color[2]) + '\0' +
                           number_text(e.strength) + '\0' + number_text(e.rotation_deg) + '\n';
  scene.file_hash = hex64(fnv1a64(text, fnv1a64(scene.file_hash)));
}

void apply_environment_overrides(Scene& scene, const EnvironmentOverrides& o) {
  if (!o.file && !o.strength && !o.rotation_deg) return;
  if (o.strength && !(std::isfinite(*o.strength) && *o.strength >= 0))
    throw Error(ExitCode::Usage, "--environment-strength " + number_text(*o.strength) + ": must be finite and >= 0");
  if (o.rotation_deg && !std::isfinite(*o.rotation_deg))
    throw Error(ExitCode::Usage, "--environment-rotation " + number_text(*o.rotation_deg) + ": must be finite");
  if (o.file && *o.file == "none") {
    scene.environment.reset();
  } else if (o.file) {
    Environment env;
    env.file = *o.file;
    env.what = "--environment";
    load_environment_image(env, *o.file, ExitCode::Usage);
    scene.environment = std::move(env);
  }
  if (!scene.environment && (o.strength || o.rotation_deg))
    throw Error(ExitCode::Usage, std::string(o.strength ? "--environment-strength" : "--environment-rotation") +
                                     ": the scene " + scene.file +
                                     " has no environment (give one with --environment FILE or an [environment] table)");
  if (!scene.environment) return;  // --environment none
  if (o.strength) scene.environment->strength = *o.strength;
  if (o.rotation_deg) scene.environment->rotation_deg = *o.rotation_deg;
  chain_environment_hash(scene);
}

}  // namespace clpt
