#include "io/render_file.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "io/image_io.h"
#include "kernels/aov_channels.h"
#include "render/aov_set.h"
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
constexpr const char* kPaths = "clpt:paths";
constexpr const char* kSegments = "clpt:segments";
constexpr const char* kPassesS = "clpt:passes_s";
constexpr const char* kPathsPerS = "clpt:paths_per_s";
constexpr const char* kSegmentsPerS = "clpt:segments_per_s";
constexpr const char* kSceneLoadS = "clpt:scene_load_s";
constexpr const char* kImageLoadS = "clpt:image_load_s";
constexpr const char* kResumeLoadS = "clpt:resume_load_s";
constexpr const char* kDiscoveryS = "clpt:discovery_s";
constexpr const char* kConvertS = "clpt:convert_s";
constexpr const char* kKernelBuildS = "clpt:kernel_build_s";
constexpr const char* kKernelBuild = "clpt:kernel_build";
constexpr const char* kFirstLaunchS = "clpt:first_launch_s";
constexpr const char* kOutputS = "clpt:output_s";
constexpr const char* kElapsedS = "clpt:elapsed_s";
constexpr const char* kPreviewExposure = "clpt:preview_exposure";
constexpr const char* kPreviewTonemap = "clpt:preview_tonemap";
constexpr const char* kAovs = "clpt:aovs";

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

// The channels `names` of `img`, n floats a pixel, when the image has all of them; else empty.
std::vector<float> take_if_present(const LoadedImage& img, const char* const* names, size_t n) {
  std::vector<int> index(n);
  for (size_t c = 0; c < n; ++c) {
    index[c] = img.channel(names[c]);
    if (index[c] < 0) return {};
  }
  const size_t pixels = size_t(img.width) * size_t(img.height), stride = img.channels.size();
  std::vector<float> out(pixels * n);
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < n; ++c) out[p * n + c] = img.pixels[p * stride + size_t(index[c])];
  return out;
}

// The first-hit layers info.aovs names (render/aov_set.h), as channels for the EXR.
std::vector<ExtraChannel> aov_channels(const Film& film, const std::string& aovs) {
  if (aovs.empty()) return {};
  const AovSet set = parse_aov_set(aovs, "clpt:aovs");
  if (!film.has_aovs()) throw Error(ExitCode::Failure, "write_render_file: the film has no first-hit layers");
  const std::vector<float> means = film.aov_means();
  const size_t pixels = film.pixel_count();
  std::vector<ExtraChannel> out;
  auto add = [&](const char* name, uint32_t channel) {
    ExtraChannel e;
    e.name = name;
    e.values.resize(pixels);
    for (size_t p = 0; p < pixels; ++p) e.values[p] = means[p * CLPT_AOV_CHANNELS + channel];
    out.push_back(std::move(e));
  };
  for (uint32_t c = 0; c < 3 && set.albedo; ++c) add(kAlbedoChannels[c], CLPT_AOV_ALBEDO + c);
  for (uint32_t c = 0; c < 3 && set.normal; ++c) add(kNormalChannels[c], CLPT_AOV_NORMAL + c);
  if (set.depth) add(kDepthChannel, CLPT_AOV_DEPTH);
  return out;
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
  put(kPaths, info.paths);
  put(kSegments, info.segments);
  auto put_real = [&m](const char* key, const std::optional<double>& value) {
    if (value) m[key] = real_text(*value);
  };
  put_real(kPassesS, info.passes_s);
  put_real(kPathsPerS, info.paths_per_s);
  put_real(kSegmentsPerS, info.segments_per_s);
  put_real(kSceneLoadS, info.scene_load_s);
  put_real(kImageLoadS, info.image_load_s);
  put_real(kResumeLoadS, info.resume_load_s);
  put_real(kDiscoveryS, info.discovery_s);
  put_real(kConvertS, info.convert_s);
  put_real(kKernelBuildS, info.kernel_build_s);
  if (!info.kernel_build.empty()) m[kKernelBuild] = info.kernel_build;
  put_real(kFirstLaunchS, info.first_launch_s);
  put_real(kOutputS, info.output_s);
  put_real(kElapsedS, info.elapsed_s);
  put_real(kPreviewExposure, info.preview_exposure);
  if (!info.preview_tonemap.empty()) m[kPreviewTonemap] = info.preview_tonemap;
  if (!info.aovs.empty()) m[kAovs] = info.aovs;
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
  info.paths = number<uint64_t>(m, kPaths);
  info.segments = number<uint64_t>(m, kSegments);
  info.passes_s = real(m, kPassesS);
  info.paths_per_s = real(m, kPathsPerS);
  info.segments_per_s = real(m, kSegmentsPerS);
  info.scene_load_s = real(m, kSceneLoadS);
  info.image_load_s = real(m, kImageLoadS);
  info.resume_load_s = real(m, kResumeLoadS);
  info.discovery_s = real(m, kDiscoveryS);
  info.convert_s = real(m, kConvertS);
  info.kernel_build_s = real(m, kKernelBuildS);
  info.kernel_build = text(m, kKernelBuild);
  info.first_launch_s = real(m, kFirstLaunchS);
  info.preview_exposure = real(m, kPreviewExposure);
  info.preview_tonemap = text(m, kPreviewTonemap);
  info.output_s = real(m, kOutputS);
  info.elapsed_s = real(m, kElapsedS);
  info.aovs = text(m, kAovs);
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
    out.albedo = take_if_present(img, kAlbedoChannels, 3);
    out.normal = take_if_present(img, kNormalChannels, 3);
    out.depth = take_if_present(img, &kDepthChannel, 1);
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
  PreviewSettings preview;
  preview.exposure_ev = info.preview_exposure.value_or(0.0);
  preview.curve = parse_tone_curve(info.preview_tonemap).value_or(ToneCurve::Clamp);
  return write_render_outputs(exr_path, film, render_metadata(info), exr_compression, preview,
                              aov_channels(film, info.aovs));
}

}  // namespace clpt
