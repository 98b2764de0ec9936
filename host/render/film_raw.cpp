#include "render/film_raw.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>

#include "util/atomic_file.h"
#include "util/error.h"

namespace clpt {

namespace {

// Writes the PFM to the temporary name for `path` (util/atomic_file.h) and returns that name.
std::string write_pfm_temporary(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  const std::string tmp = temporary_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw Error(ExitCode::OutputError, path + ": cannot write output: " + std::strerror(errno));
    // Negative scale: little-endian floats. PFM rows run bottom to top.
    out << "PF\n" << width << " " << height << "\n-1.0\n";
    for (int row = height - 1; row >= 0; --row)
      out.write(reinterpret_cast<const char*>(&rgb[size_t(row) * width * 3]),
                std::streamsize(sizeof(float)) * width * 3);
    if (!out.flush()) {
      std::remove(tmp.c_str());
      throw Error(ExitCode::OutputError, path + ": cannot write output: write failed");
    }
  }
  return tmp;
}

}  // namespace

void write_pfm_atomic(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  commit_temporary(write_pfm_temporary(path, width, height, rgb), path);
}

std::string variance_pfm_path(const std::string& path) {
  const size_t dot = path.rfind(".pfm");
  const bool ends_in_pfm = dot != std::string::npos && dot + 4 == path.size();
  return (ends_in_pfm ? path.substr(0, dot) : path) + ".var.pfm";
}

void write_film_pfm(const std::string& path, const Film& film) { write_film_pfm(path, film.mean_variance()); }

// Both files are complete before either gets its name, and neither keeps it alone: a mean whose
// variance could not be named is removed again.
void write_film_pfm(const std::string& path, const MeanVarianceImage& image) {
  const std::string variance_path = variance_pfm_path(path);
  const std::string variance_tmp = write_pfm_temporary(variance_path, image.width, image.height, image.variance);
  try {
    commit_temporary(write_pfm_temporary(path, image.width, image.height, image.mean), path);
  } catch (...) {
    std::remove(variance_tmp.c_str());
    throw;
  }
  try {
    commit_temporary(variance_tmp, variance_path);
  } catch (...) {
    std::remove(path.c_str());
    throw;
  }
}

namespace {

// One whitespace-delimited header token of a PFM (at most 32 characters).
std::string pfm_token(std::FILE* f, const std::string& path) {
  std::string token;
  int c = std::fgetc(f);
  while (c == ' ' || c == '\n' || c == '\r' || c == '\t') c = std::fgetc(f);
  while (c != EOF && c != ' ' && c != '\n' && c != '\r' && c != '\t') {
    if (token.size() >= 32) throw Error(ExitCode::Usage, path + ": not a PFM film (a header field is too long)");
    token += char(c);
    c = std::fgetc(f);
  }
  if (token.empty()) throw Error(ExitCode::Usage, path + ": not a PFM film (its header ends early)");
  return token;  // the one whitespace character after it is consumed, as the format has it
}

int pfm_dimension(const std::string& token, const char* what, const std::string& path) {
  char* end = nullptr;
  const long v = std::strtol(token.c_str(), &end, 10);
  if (*end != '\0' || v < 1 || v > 16384)
    throw Error(ExitCode::Usage, path + ": PFM " + what + " '" + token + "' is not in 1..16384");
  return int(v);
}

// A 3-channel PFM as RGB floats, row 0 at the top.
std::vector<float> read_pfm(const std::string& path, int& width, int& height) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) throw Error(ExitCode::Usage, path + ": cannot read: " + std::strerror(errno));
  if (pfm_token(f.get(), path) != "PF")
    throw Error(ExitCode::Usage, path + ": not a 3-channel PFM film (it does not start with 'PF')");
  width = pfm_dimension(pfm_token(f.get(), path), "width", path);
  height = pfm_dimension(pfm_token(f.get(), path), "height", path);
  const std::string scale_token = pfm_token(f.get(), path);
  char* end = nullptr;
  const double scale = std::strtod(scale_token.c_str(), &end);
  if (*end != '\0' || !(scale != 0) || !std::isfinite(scale))
    throw Error(ExitCode::Usage, path + ": PFM scale '" + scale_token + "' is not a non-zero number");
  const long data_begin = std::ftell(f.get());
  std::fseek(f.get(), 0, SEEK_END);
  const long length = std::ftell(f.get());
  const size_t values = size_t(width) * size_t(height) * 3;
  if (data_begin < 0 || length < 0 || size_t(length - data_begin) != values * sizeof(float))
    throw Error(ExitCode::Usage, path + ": a " + std::to_string(width) + "x" + std::to_string(height) +
                                     " PFM film must hold " + std::to_string(values * sizeof(float)) +
                                     " bytes of pixels, this one holds " + std::to_string(length - data_begin));
  std::fseek(f.get(), data_begin, SEEK_SET);
  std::vector<float> rgb(values);
  const size_t row_values = size_t(width) * 3;
  for (int row = height - 1; row >= 0; --row)  // PFM rows run bottom to top
    if (std::fread(&rgb[size_t(row) * row_values], sizeof(float), row_values, f.get()) != row_values)
      throw Error(ExitCode::Usage, path + ": cannot read its pixels");
  const bool little_endian_file = scale < 0;
  const uint16_t probe = 1;
  const bool little_endian_host = *reinterpret_cast<const uint8_t*>(&probe) == 1;
  if (little_endian_file != little_endian_host)
    for (float& v : rgb) {
      uint32_t bits;
      std::memcpy(&bits, &v, 4);
      bits = __builtin_bswap32(bits);
      std::memcpy(&v, &bits, 4);
    }
  return rgb;
}

}  // namespace

MeanVarianceImage read_film_pfm(const std::string& path) {
  MeanVarianceImage image;
  int vw = 0, vh = 0;
  image.mean = read_pfm(path, image.width, image.height);
  const std::string variance_path = variance_pfm_path(path);
  image.variance = read_pfm(variance_path, vw, vh);
  if (vw != image.width || vh != image.height)
    throw Error(ExitCode::Usage, variance_path + ": its size " + std::to_string(vw) + "x" + std::to_string(vh) +
                                     " differs from " + path + "'s " + std::to_string(image.width) + "x" +
                                     std::to_string(image.height));
  return image;
}

}  // namespace clpt
