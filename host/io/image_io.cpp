#include "io/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "util/atomic_file.h"
#include "util/error.h"

namespace clpt {
namespace {

// Writes `pixels` (channel-interleaved) to the temporary name for `path` and returns that name;
// the caller renames it into place once every output of the render has been written.
std::string write_temporary(const std::string& path, const OIIO::ImageSpec& spec,
                            OIIO::TypeDesc format, const void* pixels) {
  const std::string tmp = temporary_path_for(path);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw Error(ExitCode::OutputError, path + ": cannot write output: " + OIIO::geterror());
  if (!out->open(tmp, spec) || !out->write_image(format, pixels) || !out->close()) {
    const std::string reason = out->geterror();
    std::remove(tmp.c_str());
    throw Error(ExitCode::OutputError, path + ": cannot write output: " + reason);
  }
  return tmp;
}

std::vector<unsigned char> tone_map_preview(const std::vector<float>& rgb) {
  std::vector<unsigned char> out(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
    out[i] = static_cast<unsigned char>(std::lround(std::pow(v, 1.0f / 2.2f) * 255.0f));
  }
  return out;
}

}  // namespace

std::string preview_path_for(const std::string& exr_path) {
  return std::filesystem::path(exr_path).replace_extension(".png").string();
}

std::string write_render_outputs(const std::string& exr_path, const Film& film,
                                 const ImageMetadata& metadata) {
  const int w = film.width(), h = film.height();
  const std::vector<float> mean = film.mean_rgb();
  const std::vector<float> variance = film.variance_rgb();
  std::vector<float> pixels(size_t(w) * h * 6);
  for (size_t p = 0; p < size_t(w) * h; ++p)
    for (int c = 0; c < 3; ++c) {
      pixels[p * 6 + c] = mean[p * 3 + c];
      pixels[p * 6 + 3 + c] = variance[p * 3 + c];
    }
  OIIO::ImageSpec spec(w, h, 6, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
  spec.attribute("compression", "zip");
  for (const auto& [key, value] : metadata) spec.attribute(key, value);

  const std::string png_path = preview_path_for(exr_path);
  OIIO::ImageSpec png_spec(w, h, 3, OIIO::TypeDesc::UINT8);
  const std::vector<unsigned char> preview = tone_map_preview(mean);
  // Both files are complete before either appears under its name.
  const std::string exr_tmp = write_temporary(exr_path, spec, OIIO::TypeDesc::FLOAT, pixels.data());
  std::string png_tmp;
  try {
    png_tmp = write_temporary(png_path, png_spec, OIIO::TypeDesc::UINT8, preview.data());
  } catch (...) {
    std::remove(exr_tmp.c_str());
    throw;
  }
  commit_temporary(exr_tmp, exr_path);
  commit_temporary(png_tmp, png_path);
  return png_path;
}

int LoadedImage::channel(const std::string& name) const {
  const auto it = std::find(channels.begin(), channels.end(), name);
  return it == channels.end() ? -1 : int(it - channels.begin());
}

LoadedImage read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(ExitCode::Usage, path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  LoadedImage img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.channelnames;
  img.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
    throw Error(ExitCode::Usage, path + ": cannot read image: " + in->geterror());
  for (const OIIO::ParamValue& p : spec.extra_attribs)
    img.metadata[p.name().string()] = p.get_string();
  return img;
}

}  // namespace clpt
