// OpenImageIO-free film output: Portable Float Maps, for builds without OIIO (a borrowed GPU
// machine). `NAME.pfm` holds the mean RGB, `NAME.var.pfm` the variance of the mean; OIIO reads
// both back at home. Written atomically (temporary file, then rename).
#pragma once

#include <string>
#include <vector>

#include "render/film.h"

namespace clpt {

// 3-channel float image, RGB interleaved, row 0 at the top.
void write_pfm_atomic(const std::string& path, int width, int height, const std::vector<float>& rgb);

// Writes PATH (mean) and PATH with ".pfm" replaced by ".var.pfm" (variance of the mean).
void write_film_pfm(const std::string& path, const Film& film);

}  // namespace clpt
