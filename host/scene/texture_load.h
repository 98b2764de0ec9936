// Loading a texture's image into the scene (Scene::images): through read_scene_image (the scene
// layer's seam to image files), checked (a regular file, sane dimensions, 1 to 4 channels),
// given its device storage and colour space (texture.h), deduplicated. Both loaders use it: TOML
// `{ texture = "wood.png" }` values (scene_loader.cpp) and glTF images (gltf_material.cpp).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"
#include "scene/texture.h"

namespace clpt {

// The image file `path` (as the scene names it: `file`) as a texture of colour space `space`
// (nullopt: the file's default, default_color_space). Appended to `images` unless the same file
// in the same colour space is there already; returns its index. Throws Error(BadScene) whose
// message starts with `what` and names the file.
int load_texture_image(std::vector<TextureImage>& images, const std::string& path, const std::string& file,
                       std::optional<ColorSpace> space, const std::string& what);

// The same for an encoded image held in memory (a GLB buffer view, a data: URI): written to a
// private temporary file (util/temporary_directory.h) with the extension `extension` (".png",
// ".jpg") and read from there. `file` names it in messages ("model.glb: images[0]").
int load_texture_image_bytes(std::vector<TextureImage>& images, std::string_view bytes, const std::string& extension,
                             const std::string& file, std::optional<ColorSpace> space, const std::string& what);

// Throws Error(BadScene) naming the mesh and the material's textured key when a mesh whose
// material is textured has no texture coordinates (one per vertex).
void check_textured_meshes(const Scene& scene);

// Adds `offset` to the image index of each of the material's textures (images appended to
// another scene's list).
void offset_texture_images(Material& material, int offset);

}  // namespace clpt
