// Every image read and write of the full build goes through OpenImageIO, here: this side
// prepares pixels, names and atomic renames; the OIIO calls themselves live in a module loaded
// at run time (image_codec.h says why).
//
// A render writes OUT.exr (linear float R, G, B and the variance of each pixel mean in
// variance.R, variance.G, variance.B, plus clpt:* metadata) and OUT.png beside it (8-bit
// preview: clamp to [0, 1], then x^(1/2.2), as the book's renderer does). Both are written to a
// temporary name in the same directory and renamed, so a failed or interrupted run never leaves
// a half-written file under the requested name.
#pragma once

#include <string>
#include <vector>

#include "io/image_codec.h"
#include "render/film.h"

namespace clpt {

// Starts loading the OpenImageIO module on a background thread and returns at once, so that a
// command which will write images later (a render) does not wait for it then. Idempotent.
void preload_image_io();

// Throws Error(OutputError), naming `what` (the output) and the paths tried, when the OpenImageIO
// module is nowhere to be found; cheap (no loading). A render calls it before any work.
void check_image_io_module(const std::string& what);

// Writes the EXR at `exr_path` (channels and metadata as io/render_file.h lays them down; call
// write_render_file there) and the PNG preview with the same stem (the two at once). Returns the
// PNG path. Throws Error(OutputError) naming the file.
std::string write_render_outputs(const std::string& exr_path, const Film& film,
                                 const ImageMetadata& metadata);

// Writes an 8-bit RGB PNG (or any format the extension names), atomically.
void write_rgb8_image(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb);

// Loads the OpenImageIO module for reading `path`, or throws Error(Usage) naming the path and the
// module paths tried: a broken installation is reported before any question about the file.
void check_image_reader(const std::string& path);

// Reads any image OIIO can read. Throws Error(Usage) naming the file on failure.
LoadedImage read_image(const std::string& path);

// The PNG path for an EXR path: same directory and stem, ".png".
std::string preview_path_for(const std::string& exr_path);

}  // namespace clpt
