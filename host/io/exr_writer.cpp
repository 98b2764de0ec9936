#include "io/exr_writer.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <exception>
#include <map>

namespace clpt {
namespace {

// OpenImageIO's names for EXR compressions, which ImageToWrite::compression uses.
bool compression_from_name(const std::string& name, Imf::Compression& out) {
  static const std::map<std::string, Imf::Compression> kNames = {
      {"", Imf::ZIP_COMPRESSION},      {"zip", Imf::ZIP_COMPRESSION},    {"none", Imf::NO_COMPRESSION},
      {"rle", Imf::RLE_COMPRESSION},   {"zips", Imf::ZIPS_COMPRESSION},  {"piz", Imf::PIZ_COMPRESSION},
      {"pxr24", Imf::PXR24_COMPRESSION}};
  const auto it = kNames.find(name);
  if (it == kNames.end()) return false;
  out = it->second;
  return true;
}

}  // namespace

const std::vector<std::string>& exr_compression_names() {
  static const std::vector<std::string> kLossless = {"zip", "zips", "piz", "rle", "none"};
  return kLossless;
}

std::string write_exr(const std::string& path, const ImageToWrite& image) {
  if (image.uint8) return "clpt's EXR writer takes float channels only";
  if (image.width <= 0 || image.height <= 0 || image.channels.empty() || !image.pixels)
    return "empty image";
  Imf::Compression compression;
  if (!compression_from_name(image.compression, compression))
    return "unknown EXR compression '" + image.compression + "'";
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = compression;
    for (const auto& [key, value] : image.metadata) header.insert(key, Imf::StringAttribute(value));
    const size_t channels = image.channels.size();
    const size_t x_stride = sizeof(float) * channels;
    const size_t y_stride = x_stride * size_t(image.width);
    Imf::FrameBuffer frame;
    // OpenEXR reads through non-const pointers but does not write through them when writing.
    char* base = static_cast<char*>(const_cast<void*>(image.pixels));
    for (size_t c = 0; c < channels; ++c) {
      header.channels().insert(image.channels[c], Imf::Channel(Imf::FLOAT));
      frame.insert(image.channels[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride));
    }
    // One thread: the render's PNG is compressed beside it (image_io.cpp), on the other core.
    Imf::OutputFile file(path.c_str(), header, /*numThreads=*/0);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace clpt
