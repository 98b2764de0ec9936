// The contract of clpt's render files, written and read here only: an EXR holds the per-pixel mean
// in channels R, G, B (linear) and the variance of that mean in variance.R, variance.G,
// variance.B, plus clpt:* string metadata describing how it was made (RenderFileInfo); a raw
// NAME.pfm film holds the mean and NAME.var.pfm beside it the variance, with no metadata.
// `clpt render` writes them; `compare`, `tradeoff`, `verify` and the tests read them back.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/image_codec.h"
#include "render/film.h"

namespace clpt {

// The channels of a render EXR, in the order written.
inline constexpr const char* kMeanChannels[3] = {"R", "G", "B"};
inline constexpr const char* kVarianceChannels[3] = {"variance.R", "variance.G", "variance.B"};
// The first-hit layers a render asked for with --aovs (render/aov_set.h, docs/aovs.md), after the
// variance, each only when asked for: the albedo as an RGB layer, the shading normal as an XYZ
// layer (world space, [-1, 1]; Blender's and Nuke's layer.channel names), the depth as EXR's
// standard depth channel Z (camera-ray distance, world units; 0 where the ray found nothing).
inline constexpr const char* kAlbedoChannels[3] = {"albedo.R", "albedo.G", "albedo.B"};
inline constexpr const char* kNormalChannels[3] = {"N.X", "N.Y", "N.Z"};
inline constexpr const char* kDepthChannel = "Z";

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
  // Where the time went, in seconds of wall clock, as the render's summary prints it
  // (cli/render_summary.h); unset in files of a clpt before these keys. The parts do not overlap.
  std::optional<uint64_t> paths;            // clpt:paths, paths traced by this run (not a resumed film's)
  std::optional<uint64_t> segments;         // clpt:segments, their ray segments
  std::optional<double> passes_s;           // clpt:passes_s, the passes: their launches and the waits for them
  std::optional<double> paths_per_s;        // clpt:paths_per_s, paths / passes_s
  std::optional<double> segments_per_s;     // clpt:segments_per_s, segments / passes_s
  std::optional<double> image_load_s;       // clpt:image_load_s, the images the scene names read and
                                            // decoded (textures, environment); unset: none
  std::optional<double> scene_load_s;       // clpt:scene_load_s, the scene file and its mesh files
  std::optional<double> resume_load_s;      // clpt:resume_load_s, the --resume checkpoint (only then)
  std::optional<double> discovery_s;        // clpt:discovery_s, OpenCL devices listed and selected, the plan made
  std::optional<double> convert_s;          // clpt:convert_s, the scene converted for the kernels, its hierarchy built
  std::optional<double> kernel_build_s;     // clpt:kernel_build_s, the kernels' build (the slowest device's)
  std::string kernel_build;                 // clpt:kernel_build: compiled | clpt cache hit
  std::optional<double> first_launch_s;     // clpt:first_launch_s, the kernels' first launch, apart from the passes
  std::optional<double> output_s;           // clpt:output_s, outputs written before this file (checkpoints)
  // clpt:elapsed_s, from the command's start to when this file's metadata was made: every part
  // above and the rest, but not the writing of this file and its PNG (the summary's wall has it).
  std::optional<double> elapsed_s;
  // How the PNG preview beside the EXR was made (io/tone_map.h); the EXR itself is linear.
  std::optional<double> preview_exposure;  // clpt:preview_exposure, --exposure in EV (stops)
  std::string preview_tonemap;             // clpt:preview_tonemap: clamp | aces
  // clpt:aovs, the first-hit layers the file holds ("albedo,normal,depth", those asked for; unset
  // or "" for none). write_render_file writes their channels from the film.
  std::string aovs;
};

ImageMetadata render_metadata(const RenderFileInfo& info);
RenderFileInfo parse_render_metadata(const ImageMetadata& metadata);

struct RenderFile {
  MeanVarianceImage image;
  RenderFileInfo info;
  // The first-hit layers found in the file (by channel name): albedo and normal 3 floats a pixel,
  // depth 1; empty where the file has no such channels.
  std::vector<float> albedo, normal, depth;
};

// Reads a render EXR, or a NAME.pfm film with NAME.var.pfm. Errors are Error(Usage) and begin with
// `what` (e.g. "--reference ref.exr"; the path when empty): no such file, unreadable, a missing
// channel (named, with what the file must hold), a variance file missing or of another size.
RenderFile read_render_file(const std::string& path, const std::string& what = "");

// Writes the EXR at `exr_path` (compressed with `exr_compression`, io/exr_writer.h) and its PNG
// preview (image_io.h), with the first-hit layers info.aovs names (the film must have them,
// Film::enable_aovs; else Error(Failure)). The preview follows info.preview_exposure and
// info.preview_tonemap (unset: the book's clamp). Returns the PNG's path.
std::string write_render_file(const std::string& exr_path, const Film& film, const RenderFileInfo& info,
                              const std::string& exr_compression = "zip");

}  // namespace clpt
