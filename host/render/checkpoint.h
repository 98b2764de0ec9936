// Checkpoints: the accumulated film of a render, saved so that `clpt render --resume` can
// continue it. A small binary format of clpt's own (no OpenImageIO, so the OIIO-free build has
// it too), in the host's byte order (little-endian on every supported host), written atomically:
//
//   "CLPTCKPT" (8 bytes), u32 version (3), u32 width, u32 height, u64 spp done, u64 seed,
//   scene hash (16 hex characters: Scene::file_hash), u32 sampler (0 jitter, 1 grid, 2 sobol),
//   u32 max_bounces, u64 total samples, u64 total segments, u64 dropped samples,
//   then f64 sums (3 per pixel, RGB), f64 sums of squares (3 per pixel), f64 valid counts (1 per
//   pixel), pixels row-major with row 0 at the top; version 2 then adds the half-film of
//   render/film.h: u64 samples per pixel of half 1, f64 half-1 sums (3 per pixel), f64 half-1
//   valid counts (1 per pixel); version 3 then adds u8 adaptive (1: adaptive sampling), f64 half-1
//   sums of squares (3 per pixel) and u32 half-1 samples (1 per pixel; render/adaptive_sampling.h).
//
// Version 1 files (before the half-films) are still read: their samples all count as half 0, and
// the resumed render fills half 1 first (error_estimate.h needs both).
//
// A resumed render draws the samples an uninterrupted one would (the RNG is keyed by seed,
// pixel and sample index), so only the float rounding of pass sums can differ.
#pragma once

#include <string>

#include "render/film.h"
#include "scene/scene.h"

namespace clpt {

constexpr uint32_t kCheckpointVersion = 3;
constexpr uint32_t kOldestCheckpointVersion = 1;  // still read

// Writes `film` (between passes) and what identifies the render to `path` atomically.
// Throws Error(OutputError) naming the file.
// `adaptive`: the render samples adaptively (a resume must too).
void save_checkpoint(const std::string& path, const Scene& scene, const Film& film, bool adaptive = false);

// Reads a checkpoint and checks that it belongs to a render of `scene` with its settings
// (scene hash, width, height, seed, sampler, max_bounces, adaptive sampling). Throws Error(Usage)
// naming the file and the first mismatching field ("seed"), or saying why it cannot be read.
Film load_checkpoint(const std::string& path, const Scene& scene, bool adaptive = false);

}  // namespace clpt
