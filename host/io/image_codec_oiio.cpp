// libclpt_image_io.so: every call clpt makes into OpenImageIO (image_codec.h says why this is a
// module loaded at run time).
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>

#include "io/image_codec.h"

namespace {

std::string write_image(const std::string& path, const std::string& format_path, const clpt::ImageToWrite& image) {
  auto out = OIIO::ImageOutput::create(format_path);
  if (!out) return OIIO::geterror();
  const OIIO::TypeDesc format = image.uint8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
  OIIO::ImageSpec spec(image.width, image.height, static_cast<int>(image.channels.size()), format);
  spec.channelnames = image.channels;
  if (!image.compression.empty()) spec.attribute("compression", image.compression);
  for (const auto& [key, value] : image.metadata) spec.attribute(key, value);
  if (!out->open(path, spec) || !out->write_image(format, image.pixels) || !out->close()) return out->geterror();
  return "";
}

std::string read_image(const std::string& path, clpt::LoadedImage& img) {
  // Colours as the file stores them: OIIO would premultiply them by the alpha of a PNG, TGA or
  // TIFF ("associated" alpha) unless asked not to, and a texture's colour (glTF's base colour,
  // whose alpha is coverage: docs/gltf.md "Alpha") is not premultiplied.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.channelnames;
  img.pixel_type = spec.format.c_str();
  // No file makes clpt allocate more than its bytes can justify: deflate (PNG, EXR's zip) expands
  // at most 1032:1, and every other format OIIO reads less, so a header declaring more samples
  // than 1100 x the file's bytes (plus 1 MiB) is refused before anything is allocated.
  std::error_code ec;
  const uint64_t file_bytes = std::filesystem::file_size(path, ec);
  const uint64_t samples = uint64_t(std::max(spec.width, 0)) * uint64_t(std::max(spec.height, 0)) *
                           uint64_t(std::max(spec.nchannels, 0));
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
    return "the image declares " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " x " +
           std::to_string(spec.nchannels) + " samples";
  if (ec || samples * spec.format.size() > 1100 * file_bytes + (uint64_t(1) << 20))
    return "the image declares " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels of " +
           std::to_string(spec.nchannels) + " channels, more than its " + std::to_string(file_bytes) + " bytes can hold";
  img.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data())) return in->geterror();
  for (const OIIO::ParamValue& p : spec.extra_attribs) img.metadata[p.name().string()] = p.get_string();
  return "";
}

const clpt::ImageCodec kCodec{write_image, read_image};

}  // namespace

extern "C" __attribute__((visibility("default"))) const clpt::ImageCodec* clpt_image_codec_v1() { return &kCodec; }
