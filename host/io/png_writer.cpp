#include "io/png_writer.h"

#include <png.h>

#include <cstdio>
#include <vector>

namespace clpt {
namespace {

// libpng reports errors through a callback that must not return: it records the message and
// long-jumps back to write_png, which owns every resource and frees it there.
void on_png_error(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message;
  png_longjmp(png, 1);
}
void on_png_warning(png_structp, png_const_charp) {}

int colour_type_for(size_t channels) {
  switch (channels) {
    case 1: return PNG_COLOR_TYPE_GRAY;
    case 3: return PNG_COLOR_TYPE_RGB;
    case 4: return PNG_COLOR_TYPE_RGB_ALPHA;
    default: return -1;
  }
}

// The libpng calls, in a function of their own that holds no C++ object: the long jump of an
// error skips destructors. Errors are left in the png struct's error string by on_png_error.
void write_with_libpng(png_structp png, png_infop info, FILE* file, const ImageToWrite& image, int colour_type,
                       png_bytepp rows, png_textp texts, int text_count) {
  if (setjmp(png_jmpbuf(png)) != 0) return;
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8, colour_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (text_count > 0) png_set_text(png, info, texts, text_count);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
}

}  // namespace

std::string write_png(const std::string& path, const ImageToWrite& image) {
  const int colour_type = colour_type_for(image.channels.size());
  if (!image.uint8 || colour_type < 0) return "clpt's PNG writer takes 1, 3 or 4 channels of 8 bits";
  if (image.width <= 0 || image.height <= 0 || !image.pixels) return "empty image";
  FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return "cannot open for writing";

  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const size_t row_bytes = size_t(image.width) * image.channels.size();
  const auto* pixels = static_cast<const unsigned char*>(image.pixels);
  std::vector<png_bytep> rows(size_t(image.height));
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = const_cast<png_bytep>(pixels + y * row_bytes);
  std::vector<png_text> texts;
  for (const auto& [key, value] : image.metadata)
    texts.push_back(png_text{PNG_TEXT_COMPRESSION_NONE, const_cast<char*>(key.c_str()),
                             const_cast<char*>(value.c_str()), value.size(), 0, nullptr, nullptr});
  if (png && info)
    write_with_libpng(png, info, file, image, colour_type, rows.data(), texts.data(), int(texts.size()));
  else
    error = "out of memory";
  png_destroy_write_struct(png ? &png : nullptr, info ? &info : nullptr);
  if (std::fclose(file) != 0 && error.empty()) error = "cannot finish writing";
  return error;
}

}  // namespace clpt
