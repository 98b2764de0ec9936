#include "io/image_io.h"

#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "io/render_file.h"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <mutex>

#include "scene/scene_image.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/module_loader.h"

namespace clpt {
namespace {

constexpr const char* kModuleName = "libclpt_image_io.so";

std::vector<std::string> codec_candidates() {
#ifdef CLPT_IMAGE_IO_MODULE_PATH
  return module_candidates("CLPT_IMAGE_IO_MODULE", kModuleName, CLPT_IMAGE_IO_MODULE_PATH);
#else
  return module_candidates("CLPT_IMAGE_IO_MODULE", kModuleName, nullptr);
#endif
}

std::string cannot_load(const std::string& tried) {
  return std::string("cannot load the image I/O module ") + kModuleName +
         " (OpenImageIO), which is built beside clpt; set CLPT_IMAGE_IO_MODULE to its path. Tried:" + tried;
}

struct LoadResult {
  const ImageCodec* codec = nullptr;
  std::string error;  // when codec is null
};

LoadResult load_codec() {
  // RTLD_NOW: every OIIO symbol is bound here, on the loading thread, not at first use.
  const LoadedModule m = load_module(codec_candidates(), "clpt_image_codec_v1", RTLD_NOW | RTLD_LOCAL);
  if (!m.entry) return {nullptr, cannot_load(m.tried)};
  using Entry = const ImageCodec* (*)();
  return {reinterpret_cast<Entry>(m.entry)(), ""};
}

std::once_flag load_started;
std::shared_future<LoadResult> load_result;

void start_loading() {
  std::call_once(load_started, [] { load_result = std::async(std::launch::async, load_codec).share(); });
}

// The codec, waiting for the load; throws Error(code) naming `what` when the module is missing.
const ImageCodec& codec(ExitCode code, const std::string& what) {
  start_loading();
  const LoadResult& r = load_result.get();
  if (!r.codec) throw Error(code, what + ": " + r.error);
  return *r.codec;
}

// clpt's own writer for the format `path`'s extension names (EXR, PNG), or null: OpenImageIO's.
using OwnWriter = std::string (*)(const std::string& path, const ImageToWrite& image);
OwnWriter own_writer_for(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".exr") return write_exr;
  if (ext == ".png") return write_png;
  return nullptr;
}

// Writes `image` to the temporary name for `path` and returns that name; the caller renames it
// into place once every output has been written.
std::string write_temporary(const std::string& path, const ImageToWrite& image) {
  const std::string tmp = temporary_path_for(path);
  const OwnWriter own = own_writer_for(path);
  const std::string error = own ? own(tmp, image) : codec(ExitCode::OutputError, path).write(tmp, path, image);
  if (!error.empty()) {
    std::remove(tmp.c_str());
    throw Error(ExitCode::OutputError, path + ": cannot write output: " + error);
  }
  return tmp;
}

// An 8-bit RGB image over `rgb` (which must outlive the result).
ImageToWrite rgb8_image(int width, int height, const std::vector<unsigned char>& rgb) {
  ImageToWrite image;
  image.width = width;
  image.height = height;
  image.channels = {"R", "G", "B"};
  image.uint8 = true;
  image.pixels = rgb.data();
  return image;
}

// scene/scene_image.h's reader: read_image's pixels, at most 4 channels kept.
SceneImagePixels read_for_scene(const std::string& path) {
  LoadedImage img;
  try {
    img = read_image(path);
  } catch (const Error& e) {
    throw Error(ExitCode::BadScene, e.what());
  }
  SceneImagePixels out;
  out.width = img.width;
  out.height = img.height;
  const size_t stored = img.channels.empty() ? 0 : img.pixels.size() / (size_t(img.width) * size_t(img.height));
  if (stored == 0) throw Error(ExitCode::BadScene, path + ": image has no channels");
  out.channels = int(std::min<size_t>(stored, 4));
  out.pixel_type = img.pixel_type;
  if (size_t(out.channels) == stored) {
    out.pixels = std::move(img.pixels);
  } else {
    out.pixels.resize(size_t(img.width) * img.height * out.channels);
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
      for (int c = 0; c < out.channels; ++c) out.pixels[p * out.channels + c] = img.pixels[p * stored + c];
  }
  return out;
}

}  // namespace

void install_scene_image_reader() { set_scene_image_reader(&read_for_scene); }

int LoadedImage::channel(const std::string& name) const {
  const auto it = std::find(channels.begin(), channels.end(), name);
  return it == channels.end() ? -1 : int(it - channels.begin());
}

std::string preview_path_for(const std::string& exr_path) {
  return std::filesystem::path(exr_path).replace_extension(".png").string();
}

std::string write_render_outputs(const std::string& exr_path, const Film& film, const ImageMetadata& metadata,
                                 const std::string& exr_compression, const PreviewSettings& preview_settings,
                                 const std::vector<ExtraChannel>& extra) {
  const int w = film.width(), h = film.height();
  const std::vector<float> mean = film.mean_rgb();
  const std::vector<float> variance = film.variance_rgb();
  const size_t stride = 6 + extra.size();
  std::vector<float> pixels(size_t(w) * h * stride);
  for (size_t p = 0; p < size_t(w) * h; ++p) {
    for (int c = 0; c < 3; ++c) {
      pixels[p * stride + c] = mean[p * 3 + c];
      pixels[p * stride + 3 + c] = variance[p * 3 + c];
    }
    for (size_t e = 0; e < extra.size(); ++e) pixels[p * stride + 6 + e] = extra[e].values[p];
  }
  ImageToWrite exr;
  exr.width = w;
  exr.height = h;
  exr.channels.assign(std::begin(kMeanChannels), std::end(kMeanChannels));
  exr.channels.insert(exr.channels.end(), std::begin(kVarianceChannels), std::end(kVarianceChannels));
  for (const ExtraChannel& e : extra) exr.channels.push_back(e.name);
  exr.pixels = pixels.data();
  exr.compression = exr_compression;
  exr.metadata = metadata;

  const std::string png_path = preview_path_for(exr_path);
  const std::vector<unsigned char> preview = tone_map_preview(mean, preview_settings);
  const ImageToWrite png = rgb8_image(w, h, preview);

  // The two files are compressed at once (each is single-threaded zlib), and both are complete
  // before either appears under its name.
  auto png_written = std::async(std::launch::async, [&] { return write_temporary(png_path, png); });
  std::string exr_tmp, png_tmp;
  try {
    exr_tmp = write_temporary(exr_path, exr);
  } catch (...) {
    try {
      std::remove(png_written.get().c_str());
    } catch (...) {
    }
    throw;
  }
  try {
    png_tmp = png_written.get();
  } catch (...) {
    std::remove(exr_tmp.c_str());
    throw;
  }
  try {
    commit_temporary(exr_tmp, exr_path);
  } catch (...) {
    std::remove(png_tmp.c_str());
    throw;
  }
  commit_temporary(png_tmp, png_path);
  return png_path;
}

void write_rgb8_image(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb) {
  commit_temporary(write_temporary(path, rgb8_image(width, height, rgb)), path);
}

void check_image_reader(const std::string& path) { codec(ExitCode::Usage, path); }

namespace {
// "" unless `path` is a PNG file (by its signature) that does not end with its IEND chunk, as every
// whole PNG does: a truncated one. Checked before the codec reads it, with a message that says so;
// OpenImageIO 2.4's PNG reader also leaks a string when libpng meets the early end (LeakSanitizer,
// scripts/sanitize.sh).
std::string png_truncation(const std::string& path) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const unsigned char kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return "";  // the codec names what is wrong
  unsigned char head[8] = {}, tail[12] = {};
  const bool png = std::fread(head, 1, 8, f) == 8 && std::equal(head, head + 8, kSignature);
  const bool whole = png && std::fseek(f, -12, SEEK_END) == 0 && std::fread(tail, 1, 12, f) == 12 &&
                     std::equal(tail, tail + 12, kIend);
  std::fclose(f);
  return png && !whole ? "a PNG file ends with its IEND chunk and this one does not (truncated?)" : "";
}
}  // namespace

LoadedImage read_image(const std::string& path) {
  const ImageCodec& c = codec(ExitCode::Usage, path);
  if (const std::string truncated = png_truncation(path); !truncated.empty())
    throw Error(ExitCode::Usage, path + ": cannot read image: " + truncated);
  LoadedImage img;
  const std::string error = c.read(path, img);
  if (!error.empty()) throw Error(ExitCode::Usage, path + ": cannot read image: " + error);
  return img;
}

}  // namespace clpt
