// glTF materials (glTF 2.0 section 3.9) as clpt's MaterialType::Pbr: the metallic-roughness
// factors, emissiveFactor x KHR_materials_emissive_strength, KHR_materials_ior,
// KHR_materials_transmission and KHR_materials_volume, doubleSided. Factors only: textures are
// a later issue (a warning lists the materials that have them), and alpha is not rendered (a
// warning lists the materials whose alpha would matter).
#pragma once

#include "scene/tinygltf_config.h"

#include <string>
#include <vector>

#include "scene/scene.h"

namespace clpt {

// Every material of the file, in order, each value checked against the schema's range; warnings
// ("ELEMENT: MESSAGE") appended to `warnings`.
std::vector<Material> convert_materials(const tinygltf::Model& model, std::vector<std::string>& warnings);

}  // namespace clpt
