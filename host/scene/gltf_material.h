// glTF materials (glTF 2.0 section 3.9) as clpt's MaterialType::Pbr: the metallic-roughness
// factors, emissiveFactor x KHR_materials_emissive_strength, KHR_materials_ior,
// KHR_materials_transmission and KHR_materials_volume, doubleSided, and the textures below.
// alphaMode, alphaCutoff and baseColorFactor's alpha (MaterialTextures; rendered as coverage,
// kernels/alpha.cl). The occlusion texture is not read (a path tracer computes occlusion).
#pragma once

#include "scene/tinygltf_config.h"

#include <string>
#include <vector>

#include "scene/scene.h"

namespace clpt {

// The highest texture coordinate set (TEXCOORD_n) a texture may name: glTF allows any n, exporters
// write one or two; a larger texCoord is refused rather than looked up.
constexpr int kMaxUvSet = 15;

// Every material of the file, in order, each value checked against the schema's range; warnings
// ("ELEMENT: MESSAGE") appended to `warnings`. Textures (docs/textures.md): baseColorTexture,
// metallicRoughnessTexture, emissiveTexture and normalTexture with their samplers and
// KHR_texture_transform; their images (external files beside `path`, the GLB's buffer views,
// data: URIs) are decoded into `images`.
std::vector<Material> convert_materials(const tinygltf::Model& model, const std::string& path,
                                        std::vector<TextureImage>& images, std::vector<std::string>& warnings);

}  // namespace clpt
