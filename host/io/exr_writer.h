// clpt's own EXR writer, through the OpenEXR library itself (the library OpenImageIO uses for EXR).
// Why not OpenImageIO for this one format: loading OIIO's module binds about 260 shared libraries,
// 0.25 s of CPU in every render that writes an EXR, while OpenEXR alone loads in a few
// milliseconds (docs/performance.md, "Fixed costs"). The files are the same EXR either way: every
// reader of clpt's renders (render_file.h) still reads them through OpenImageIO.
#pragma once

#include <string>
#include <vector>

#include "io/image_codec.h"

namespace clpt {

// Writes `image` (float channels, interleaved, row 0 at the top) as a scan-line EXR of 32-bit
// float channels at `path`, with `image.compression` ("zip", "piz", "none", ...; "" is zip) and
// every metadata entry as a string attribute. Returns "" or the reason it failed; never throws.
std::string write_exr(const std::string& path, const ImageToWrite& image);

// The lossless compressions a render's EXR may be written with (--exr-compression), zip first
// (the default). Measured on clpt's films (docs/performance.md, "Fixed costs"): noisy float
// channels shrink by 5-8% under zip, for about 0.1 CPU s per 640x480 film; none writes fastest.
const std::vector<std::string>& exr_compression_names();

}  // namespace clpt
