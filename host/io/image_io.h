// Every image read and write of the full build, here: this side prepares pixels, names and atomic
// renames. EXR and PNG are written by clpt's own writers (exr_writer.h through OpenEXR,
// png_writer.h through libpng), so a render never loads OpenImageIO; every read, and a write in
// any other format, goes through OpenImageIO, whose calls live in a module loaded at run time
// (image_codec.h says why).
//
// A render writes OUT.exr (linear float R, G, B and the variance of each pixel mean in
// variance.R, variance.G, variance.B, plus clpt:* metadata) and OUT.png beside it (8-bit
// preview: clamp to [0, 1], then x^(1/2.2), as the book's renderer does; --exposure and --tonemap
// change it, io/tone_map.h). Both are written to a
// temporary name in the same directory and renamed, so a failed or interrupted run never leaves
// a half-written file under the requested name.
#pragma once

#include <string>
#include <vector>

#include "io/image_codec.h"
#include "io/tone_map.h"
#include "render/film.h"

namespace clpt {

// One more float channel of a render's EXR, one value a pixel (the first-hit layers,
// io/render_file.h names them).
struct ExtraChannel {
  std::string name;
  std::vector<float> values;
};

// Writes the EXR at `exr_path` (channels and metadata as io/render_file.h lays them down; call
// write_render_file there) and the PNG preview with the same stem (the two at once), the EXR with
// `exr_compression` (io/exr_writer.h, exr_compression_names) and the `extra` channels after the
// mean and variance, the PNG as `preview` says (io/tone_map.h). Returns the PNG path. Throws
// Error(OutputError) naming the file.
std::string write_render_outputs(const std::string& exr_path, const Film& film, const ImageMetadata& metadata,
                                 const std::string& exr_compression = "zip", const PreviewSettings& preview = {},
                                 const std::vector<ExtraChannel>& extra = {});

// Writes an 8-bit RGB PNG (or any format the extension names, through OpenImageIO), atomically.
void write_rgb8_image(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb);

// Loads the OpenImageIO module for reading `path`, or throws Error(Usage) naming the path and the
// module paths tried: a broken installation is reported before any question about the file.
void check_image_reader(const std::string& path);

// Reads any image OIIO can read. Throws Error(Usage) naming the file on failure.
LoadedImage read_image(const std::string& path);

// Installs read_image as the scene layer's image reader (scene/scene_image.h): a scene's texture
// or environment file that cannot be read is then Error(BadScene) naming the file.
void install_scene_image_reader();

// The PNG path for an EXR path: same directory and stem, ".png".
std::string preview_path_for(const std::string& exr_path);

}  // namespace clpt
