#include "io/exr_writer.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <exception>
#include <map>
#include <thread>

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

// The cores OpenEXR's global thread pool gets, set up once (at most 8: a 640x480 image is 30
// blocks).
int exr_threads() {
  static const int threads = [] {
    const int n = std::clamp(int(std::thread::hardware_concurrency()), 1, 8);
    if (n > 1) Imf::setGlobalThreadCount(n);
    return n > 1 ? n : 0;
  }();
  return threads;
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
    // Its blocks of 16 lines are compressed on every core: the EXR's zlib is most of the time of
    // writing a render (the PNG beside it, image_io.cpp, is a quarter of that), so the PNG and
    // the EXR's blocks share the cores (docs/performance.md, "Fixed costs").
    const int threads = exr_threads();
    Imf::OutputFile file(path.c_str(), header, threads);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace clpt
