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

// PATH with ".pfm" replaced by ".var.pfm" (or ".var.pfm" appended): where a film's variance goes.
std::string variance_pfm_path(const std::string& path);

// Writes PATH (mean) and variance_pfm_path(PATH) (variance of the mean): both, or (throwing
// Error(OutputError)) neither.
void write_film_pfm(const std::string& path, const Film& film);
void write_film_pfm(const std::string& path, const MeanVarianceImage& image);

// Reads what write_film_pfm wrote: PATH's mean and variance_pfm_path(PATH)'s variance, both
// 3-channel PFMs of one size (either byte order). Throws Error(Usage) naming the file for a
// missing or malformed file, sizes that differ, or a size above 16384 per side (checked before
// anything is allocated, and against the file's length).
MeanVarianceImage read_film_pfm(const std::string& path);

}  // namespace clpt
