// The contract of clpt's render files, written and read here only: an EXR holds the per-pixel mean
// in channels R, G, B (linear) and the variance of that mean in variance.R, variance.G,
// variance.B, plus clpt:* string metadata describing how it was made (RenderFileInfo); a raw
// NAME.pfm film holds the mean and NAME.var.pfm beside it the variance, with no metadata.
// `clpt render` writes them; `compare`, `tradeoff`, `verify` and the tests read them back.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "io/image_codec.h"
#include "render/film.h"

namespace clpt {

// The channels of a render EXR, in the order written.
inline constexpr const char* kMeanChannels[3] = {"R", "G", "B"};
inline constexpr const char* kVarianceChannels[3] = {"variance.R", "variance.G", "variance.B"};

// What the clpt:* metadata says about a render. Numbers are unset when a file lacks the key (an
// EXR made by another program, such as the book renderer's references) or holds no number there.
struct RenderFileInfo {
  std::string version;                  // clpt:version, the clpt that wrote it
  std::optional<uint64_t> spp;          // clpt:spp, samples per pixel in the film
  std::optional<uint64_t> seed;         // clpt:seed
  std::string scene;                    // clpt:scene, the scene file's path as given
  std::string scene_hash;               // clpt:scene_hash, of the scene file's contents
  std::string device;                   // clpt:device, label(s) of the device(s)
  std::string precision;                // clpt:precision, fast | robust | double
  std::optional<int64_t> rr_from;       // clpt:rr_from, -1 for no Russian roulette
  std::string estimator;                // clpt:estimator, book | nee
  std::string sampler;                  // clpt:sampler, jitter | grid | sobol | sobol-grid
  bool adaptive = false;                // clpt:adaptive = 1: adaptive sampling (render/adaptive_sampling.h)
  std::optional<uint64_t> max_bounces;  // clpt:max_bounces
  std::optional<uint64_t> dropped_samples;  // clpt:dropped_samples, NaN/Inf samples left out
  bool interrupted = false;             // clpt:interrupted = 1: spp counts the finished passes only
  // clpt:error_estimate, clpt's estimate of the image's relative RMSE against the converged image
  // (the upper estimate of render/error_estimate.h, what --target-error compares); unset when no
  // estimate exists (one pass).
  std::optional<double> error_estimate;
  std::optional<double> target_error;   // clpt:target_error, the --target-error asked for
  std::string stop;                     // clpt:stop: sample count | time limit | target error
};

ImageMetadata render_metadata(const RenderFileInfo& info);
RenderFileInfo parse_render_metadata(const ImageMetadata& metadata);

struct RenderFile {
  MeanVarianceImage image;
  RenderFileInfo info;
};

// Reads a render EXR, or a NAME.pfm film with NAME.var.pfm. Errors are Error(Usage) and begin with
// `what` (e.g. "--reference ref.exr"; the path when empty): no such file, unreadable, a missing
// channel (named, with what the file must hold), a variance file missing or of another size.
RenderFile read_render_file(const std::string& path, const std::string& what = "");

// Writes the EXR at `exr_path` (compressed with `exr_compression`, io/exr_writer.h) and its PNG
// preview (image_io.h). Returns the PNG's path.
std::string write_render_file(const std::string& exr_path, const Film& film, const RenderFileInfo& info,
                              const std::string& exr_compression = "zip");

}  // namespace clpt
