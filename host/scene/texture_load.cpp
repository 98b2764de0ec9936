// Texture images into the scene (texture_load.h).
#include "scene/texture_load.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "scene/scene_image.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/temporary_directory.h"

namespace clpt {
namespace {

[[noreturn]] void fail(const std::string& what, const std::string& file, const std::string& message) {
  throw Error(ExitCode::BadScene, what + ": " + file + ": " + message);
}

// The decoded image checked and converted; `hash` of its encoded bytes.
int add_image(std::vector<TextureImage>& images, SceneImagePixels pixels, const std::string& file, const std::string& hash,
              std::optional<ColorSpace> space, const std::string& what) {
  if (pixels.width <= 0 || pixels.height <= 0 || pixels.width > kMaxTextureDimension || pixels.height > kMaxTextureDimension ||
      uint64_t(pixels.width) * uint64_t(pixels.height) > kMaxTexturePixels)
    fail(what, file, std::to_string(pixels.width) + " x " + std::to_string(pixels.height) +
                         " pixels: a texture is at most " + std::to_string(kMaxTextureDimension) + " pixels wide and high and " +
                         std::to_string(kMaxTexturePixels) + " pixels in all");
  if (pixels.channels < 1 || pixels.channels > 4) fail(what, file, std::to_string(pixels.channels) + " channels (1 to 4 are read)");
  if (pixels.pixels.size() != size_t(pixels.width) * size_t(pixels.height) * size_t(pixels.channels))
    fail(what, file, "the reader returned a short image");
  const ColorSpace color_space = space.value_or(default_color_space(pixels.pixel_type));
  for (size_t i = 0; i < images.size(); ++i)
    if (images[i].file == file && images[i].hash == hash && images[i].color_space == color_space) return int(i);
  TextureImage image;
  image.file = file;
  image.hash = hash;
  image.width = pixels.width;
  image.height = pixels.height;
  image.channels = pixels.channels;
  image.storage = storage_for(pixels.pixel_type);
  image.color_space = color_space;
  image.pixels = std::move(pixels.pixels);
  for (float& v : image.pixels)
    if (!std::isfinite(v)) fail(what, file, "the image has a sample that is not finite");
  // Only 8-bit texels stay sRGB-encoded (decoded per texel on the device); half and float hold
  // linear values. The colour channels: all of 1 and 3, the first of 2 (grey, alpha), three of 4.
  if (color_space == ColorSpace::Srgb && image.storage != TexelStorage::U8) {
    const int colours = image.channels == 2 ? 1 : image.channels == 4 ? 3 : image.channels;
    for (size_t p = 0; p < image.pixels.size(); p += size_t(image.channels))
      for (int c = 0; c < colours; ++c) image.pixels[p + c] = float(srgb_to_linear(image.pixels[p + c]));
  }
  images.push_back(std::move(image));
  return int(images.size() - 1);
}

}  // namespace

int load_texture_image(std::vector<TextureImage>& images, const std::string& path, const std::string& file,
                       std::optional<ColorSpace> space, const std::string& what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) fail(what, file, "no such file");
  if (!std::filesystem::is_regular_file(status)) fail(what, file, "not a regular file");
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(what, file, "cannot read its size: " + ec.message());
  if (size == 0) fail(what, file, "the file is empty");
  if (size > (uint64_t(1) << 30)) fail(what, file, "the file is over 1 GiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(what, file, "cannot open it");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() != size) fail(what, file, "cannot read it whole");
  SceneImagePixels pixels = read_scene_image(path, what);
  return add_image(images, std::move(pixels), file, hex64(fnv1a64(bytes)), space, what);
}

int load_texture_image_bytes(std::vector<TextureImage>& images, std::string_view bytes, const std::string& extension,
                             const std::string& file, std::optional<ColorSpace> space, const std::string& what) {
  if (bytes.empty()) fail(what, file, "the image has no bytes");
  TemporaryDirectory dir("clpt-texture");
  const std::string path = dir.file("image" + extension);
  {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) throw Error(ExitCode::Failure, what + ": " + file + ": cannot write a temporary copy to " + path);
  }
  SceneImagePixels pixels;
  try {
    pixels = read_scene_image(path, what);
  } catch (const Error& e) {
    // The temporary file's name means nothing to the user: name the element instead.
    std::string message = e.what();
    for (size_t at = message.find(path); at != std::string::npos; at = message.find(path)) message.replace(at, path.size(), file);
    throw Error(e.code(), message);
  }
  return add_image(images, std::move(pixels), file, hex64(fnv1a64(bytes)), space, what);
}

void check_textured_meshes(const Scene& scene) {
  for (const TriangleMesh& mesh : scene.meshes) {
    const MaterialTextures& t = mesh.material.textures;
    if (!t.any() || mesh.uvs.size() == mesh.positions.size()) continue;
    const TextureRef* named = nullptr;
    for (const TextureRef* r : {&t.base_color, &t.metallic, &t.roughness, &t.emission, &t.normal})
      if (!named && r->used()) named = r;
    const std::string mesh_name = mesh.gltf_element.empty() ? mesh.where.str() + ": mesh '" + mesh.name + "'"
                                                            : mesh.file + ": " + mesh.gltf_element;
    throw Error(ExitCode::BadScene, mesh_name + " has no texture coordinates" +
                                        (mesh.file.empty() || !mesh.gltf_element.empty() ? "" : " (" + mesh.file + " has none)") +
                                        ", and its material is textured: " + named->where);
  }
}

void offset_texture_images(Material& material, int offset) {
  MaterialTextures& t = material.textures;
  for (TextureRef* r : {&t.base_color, &t.metallic, &t.roughness, &t.emission, &t.normal})
    if (r->used()) r->image += offset;
}

}  // namespace clpt
