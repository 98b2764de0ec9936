// libclpt_image_io.so: every call clpt makes into OpenImageIO (image_codec.h says why this is a
// module loaded at run time).
#include <OpenImageIO/imageio.h>

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
  auto in = OIIO::ImageInput::open(path);
  if (!in) return OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.channelnames;
  img.pixel_type = spec.format.c_str();
  img.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data())) return in->geterror();
  for (const OIIO::ParamValue& p : spec.extra_attribs) img.metadata[p.name().string()] = p.get_string();
  return "";
}

const clpt::ImageCodec kCodec{write_image, read_image};

}  // namespace

extern "C" __attribute__((visibility("default"))) const clpt::ImageCodec* clpt_image_codec_v1() { return &kCodec; }
