#include "io/render_file.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "io/image_io.h"
#include "render/film_raw.h"
#include "util/error.h"

namespace clpt {
namespace {

// The clpt:* keys, each named once.
constexpr const char* kVersion = "clpt:version";
constexpr const char* kSpp = "clpt:spp";
constexpr const char* kSeed = "clpt:seed";
constexpr const char* kScene = "clpt:scene";
constexpr const char* kSceneHash = "clpt:scene_hash";
constexpr const char* kDevice = "clpt:device";
constexpr const char* kPrecision = "clpt:precision";
constexpr const char* kRrFrom = "clpt:rr_from";
constexpr const char* kEstimator = "clpt:estimator";
constexpr const char* kSampler = "clpt:sampler";
constexpr const char* kMaxBounces = "clpt:max_bounces";
constexpr const char* kDroppedSamples = "clpt:dropped_samples";
constexpr const char* kInterrupted = "clpt:interrupted";
constexpr const char* kErrorEstimate = "clpt:error_estimate";
constexpr const char* kTargetError = "clpt:target_error";
constexpr const char* kStop = "clpt:stop";
constexpr const char* kAdaptive = "clpt:adaptive";

std::string text(const ImageMetadata& m, const char* key) {
  const auto it = m.find(key);
  return it == m.end() ? std::string() : it->second;
}

template <typename T>
std::optional<T> number(const ImageMetadata& m, const char* key) {
  const std::string s = text(m, key);
  if (s.empty()) return std::nullopt;
  try {
    size_t used = 0;
    const long long v = std::stoll(s, &used);
    if (used != s.size() || (std::is_unsigned_v<T> && v < 0)) return std::nullopt;
    return T(v);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// A finite real number written in full precision (%.9g), or unset when the key is missing or
// holds something else.
std::string real_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::optional<double> real(const ImageMetadata& m, const char* key) {
  const std::string s = text(m, key);
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// Three named channels of `img`, 3 floats a pixel; a missing one is named in the error.
std::vector<float> take_rgb(const LoadedImage& img, const std::string& what, const char* const (&names)[3],
                            const char* holds) {
  int index[3];
  for (int c = 0; c < 3; ++c) {
    index[c] = img.channel(names[c]);
    if (index[c] < 0)
      throw Error(ExitCode::Usage, what + ": no channel '" + names[c] + "'; " + holds);
  }
  const size_t pixels = size_t(img.width) * size_t(img.height), stride = img.channels.size();
  std::vector<float> rgb(pixels * 3);
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = img.pixels[p * stride + size_t(index[c])];
  return rgb;
}

constexpr const char* kRenderHolds =
    "a render file holds the mean (R, G, B) and its variance (variance.R, variance.G, variance.B) as "
    "`clpt render` writes them";

}  // namespace

ImageMetadata render_metadata(const RenderFileInfo& info) {
  ImageMetadata m = {
      {kVersion, info.version},   {kScene, info.scene},         {kSceneHash, info.scene_hash},
      {kDevice, info.device},     {kPrecision, info.precision}, {kEstimator, info.estimator},
      {kSampler, info.sampler},
  };
  auto put = [&m](const char* key, const auto& value) {
    if (value) m[key] = std::to_string(*value);
  };
  put(kSpp, info.spp);
  put(kSeed, info.seed);
  put(kRrFrom, info.rr_from);
  put(kMaxBounces, info.max_bounces);
  put(kDroppedSamples, info.dropped_samples);
  if (info.interrupted) m[kInterrupted] = "1";
  if (info.adaptive) m[kAdaptive] = "1";
  if (info.error_estimate) m[kErrorEstimate] = real_text(*info.error_estimate);
  if (info.target_error) m[kTargetError] = real_text(*info.target_error);
  if (!info.stop.empty()) m[kStop] = info.stop;
  return m;
}

RenderFileInfo parse_render_metadata(const ImageMetadata& m) {
  RenderFileInfo info;
  info.version = text(m, kVersion);
  info.spp = number<uint64_t>(m, kSpp);
  info.seed = number<uint64_t>(m, kSeed);
  info.scene = text(m, kScene);
  info.scene_hash = text(m, kSceneHash);
  info.device = text(m, kDevice);
  info.precision = text(m, kPrecision);
  info.rr_from = number<int64_t>(m, kRrFrom);
  info.estimator = text(m, kEstimator);
  info.sampler = text(m, kSampler);
  info.max_bounces = number<uint64_t>(m, kMaxBounces);
  info.dropped_samples = number<uint64_t>(m, kDroppedSamples);
  info.interrupted = text(m, kInterrupted) == "1";
  info.adaptive = text(m, kAdaptive) == "1";
  info.error_estimate = real(m, kErrorEstimate);
  info.target_error = real(m, kTargetError);
  info.stop = text(m, kStop);
  return info;
}

RenderFile read_render_file(const std::string& path, const std::string& what_given) {
  const std::string what = what_given.empty() ? path : what_given;
  check_image_reader(path);
  if (!std::filesystem::is_regular_file(path)) throw Error(ExitCode::Usage, what + ": no such file");
  LoadedImage img;
  try {
    img = read_image(path);
  } catch (const Error& e) {
    throw Error(ExitCode::Usage, what_given.empty() ? std::string(e.what()) : what_given + ": " + e.what());
  }
  RenderFile out;
  out.image.width = img.width;
  out.image.height = img.height;
  out.image.mean = take_rgb(img, what, kMeanChannels, kRenderHolds);
  out.info = parse_render_metadata(img.metadata);
  if (std::filesystem::path(path).extension() != ".pfm") {
    out.image.variance = take_rgb(img, what, kVarianceChannels, kRenderHolds);
    return out;
  }
  const std::string variance_path = variance_pfm_path(path);
  if (!std::filesystem::exists(variance_path))
    throw Error(ExitCode::Usage, what + ": no variance file " + variance_path + " beside this raw film");
  const LoadedImage variance = read_image(variance_path);
  if (variance.width != img.width || variance.height != img.height)
    throw Error(ExitCode::Usage, variance_path + ": its size differs from " + path);
  out.image.variance = take_rgb(variance, variance_path, kMeanChannels, "the variance of a raw film is RGB");
  return out;
}

std::string write_render_file(const std::string& exr_path, const Film& film, const RenderFileInfo& info,
                              const std::string& exr_compression) {
  return write_render_outputs(exr_path, film, render_metadata(info), exr_compression);
}

}  // namespace clpt
