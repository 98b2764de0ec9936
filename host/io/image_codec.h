// The boundary between clpt and OpenImageIO: the only calls into OIIO, in a module loaded at run
// time (libclpt_image_io.so, image_codec_oiio.cpp), and the loader that finds it (image_io.cpp).
//
// Why a module: Debian's OpenImageIO links about 260 shared libraries (video, DICOM, OpenVDB,
// camera raw, ...), all bound at load time; loading them took 0.39 s of every process on the
// project's 2-core VM, `clpt --help` included. Linked at run time, OIIO costs nothing to commands
// that read no image, and `clpt render`, whose EXR and PNG clpt writes itself (exr_writer.h,
// png_writer.h), never loads it.
//
// Contract: both sides are built from this tree by the same compiler (the module is a build
// product beside the clpt executable), so C++ types cross the boundary; errors come back as text,
// never as exceptions.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace clpt {

using ImageMetadata = std::map<std::string, std::string>;

// An image as read: every channel as float, interleaved, row 0 at the top.
struct LoadedImage {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;
  std::vector<float> pixels;  // channel-interleaved, row 0 at the top
  std::string pixel_type;     // the file's sample type as OpenImageIO names it ("uint8", "half", "float", ...)
  ImageMetadata metadata;     // string form of every attribute
  // Index of a named channel, or -1.
  int channel(const std::string& name) const;
};

// An image to write: `channels.size()` interleaved channels of float or 8-bit values.
struct ImageToWrite {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;
  bool uint8 = false;          // false: float
  const void* pixels = nullptr;
  std::string compression;     // OIIO "compression" attribute; "" for the format's default
  ImageMetadata metadata;      // written as string attributes
};

struct ImageCodec {
  // Writes `image` to the file `path`, in the format that `format_path`'s extension names (the
  // file is written under a temporary name, then renamed). Returns "" or OIIO's error.
  std::string (*write)(const std::string& path, const std::string& format_path, const ImageToWrite& image);
  // Reads any image OIIO can read into `out`. Returns "" or OIIO's error.
  std::string (*read)(const std::string& path, LoadedImage& out);
};

}  // namespace clpt

// The module's one entry point (the version in the name changes with ImageCodec).
extern "C" const clpt::ImageCodec* clpt_image_codec_v1();
