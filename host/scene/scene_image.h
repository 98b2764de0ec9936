// The images a scene refers to (textures, the environment), as the scene layer reads them: the
// seam between the scene layer and image files. Decoding belongs to host/io (OpenImageIO, in a
// module loaded at run time: io/image_codec.h), a layer above this one, so io installs its reader
// here at start-up (io/image_io.h, install_scene_image_reader; clpt's main and the test runner do);
// a build without OpenImageIO has none, and a scene that names an image is then refused with a
// message that says so. The scene layer never sees OpenImageIO's types.
#pragma once

#include <string>
#include <vector>

namespace clpt {

// An image file decoded to float, channel-interleaved, row 0 at the top of the picture.
struct SceneImagePixels {
  int width = 0;
  int height = 0;
  int channels = 0;         // 1 to 4 as stored in the file (more are cut to 4 by the reader)
  std::string pixel_type;   // the file's own sample type: "uint8", "uint16", "half", "float", ...
  std::vector<float> pixels;  // width * height * channels; 8- and 16-bit samples as value / max
};

// Reads `path`; throws clpt::Error naming `path` when it cannot. The installed reader decides
// the exit code (io: ExitCode::BadScene for a scene's image).
using SceneImageReader = SceneImagePixels (*)(const std::string& path);

// Installs the reader (once, before scenes load); nullptr removes it.
void set_scene_image_reader(SceneImageReader reader);

// Reads an image a scene names, through the installed reader. `what` names the referring key or
// element for the message ("scene.toml:4:1: environment.file"). Throws Error(BadScene) when no
// reader is installed (a build without OpenImageIO), or the reader's error.
SceneImagePixels read_scene_image(const std::string& path, const std::string& what);

// Wall seconds this process has spent in read_scene_image so far (the render summary's "image
// load", apart from the rest of the scene's loading).
double scene_image_seconds();

}  // namespace clpt
