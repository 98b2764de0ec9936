// Every image read and write of the full build goes through OpenImageIO, here.
//
// A render writes OUT.exr (linear float R, G, B and the variance of each pixel mean in
// variance.R, variance.G, variance.B, plus clpt:* metadata) and OUT.png beside it (8-bit
// preview: clamp to [0, 1], then x^(1/2.2), as the book's renderer does). Both are written to a
// temporary name in the same directory and renamed, so a failed or interrupted run never leaves
// a half-written file under the requested name.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "render/film.h"

namespace clpt {

using ImageMetadata = std::map<std::string, std::string>;

// Writes the EXR at `exr_path` and the PNG preview with the same stem. Returns the PNG path.
std::string write_render_outputs(const std::string& exr_path, const Film& film,
                                 const ImageMetadata& metadata);

struct LoadedImage {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;
  std::vector<float> pixels;  // channel-interleaved, row 0 at the top
  ImageMetadata metadata;     // string form of every attribute
  // Index of a named channel, or -1.
  int channel(const std::string& name) const;
};

// Reads any image OIIO can read. Throws Error(BadScene-like Usage) naming the file on failure.
LoadedImage read_image(const std::string& path);

// The PNG path for an EXR path: same directory and stem, ".png".
std::string preview_path_for(const std::string& exr_path);

}  // namespace clpt
