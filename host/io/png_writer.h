// clpt's own PNG writer, through libpng: the 8-bit previews beside every render and compare's
// difference picture. For the same reason as exr_writer.h: a render that writes its outputs never
// loads OpenImageIO's module.
#pragma once

#include <string>

#include "io/image_codec.h"

namespace clpt {

// Writes `image` (8-bit channels: 1 grey, 3 RGB or 4 RGBA, interleaved, row 0 at the top) as a PNG
// at `path`. Metadata entries become tEXt chunks. Returns "" or the reason it failed; never throws.
std::string write_png(const std::string& path, const ImageToWrite& image);

}  // namespace clpt
