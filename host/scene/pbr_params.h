// The Pbr material's parameters, declared once: each TOML key of a `type = "pbr"` material, the
// Material field it fills, its range and its default. The loader reads exactly these keys
// (scene_loader.cpp), the validator checks these ranges (scene_validate.cpp) and the writer writes
// these keys back (scene_writer.cpp). The device's copy of each is a GpuMaterial field
// (kernels/types.h, filled in device_scene.cpp).
#pragma once

#include <limits>

#include "scene/scene.h"

namespace clpt {

// A number of the material: in [min, max], `fallback` when the key is absent (glTF's default).
struct PbrNumber {
  const char* key;
  double Material::*field;
  double min;
  double max;
  double fallback;
};

// A colour: `max_one` for a reflectance ([0, 1] per channel), else >= 0 per channel.
struct PbrColour {
  const char* key;
  Vec3 Material::*field;
  bool max_one;
  Vec3 fallback;
};

inline constexpr double kPbrUnbounded = std::numeric_limits<double>::max();

inline const PbrNumber kPbrNumbers[] = {
    {"metallic", &Material::metallic, 0, 1, 1},
    {"roughness", &Material::roughness, 0, 1, 1},
    {"ior", &Material::ior, 1, 10, 1.5},
    {"transmission", &Material::transmission, 0, 1, 0},
    // KHR_materials_volume: 0 thin-walled; attenuation_distance 0 stands for glTF's infinity.
    {"thickness", &Material::thickness, 0, kPbrUnbounded, 0},
    {"attenuation_distance", &Material::attenuation_distance, 0, kPbrUnbounded, 0},
};

inline const PbrColour kPbrColours[] = {
    {"base_color", &Material::reflectance, true, {1, 1, 1}},
    {"emission", &Material::emission, false, {0, 0, 0}},
    {"attenuation_color", &Material::attenuation_color, true, {1, 1, 1}},
};

// The one boolean key, glTF's doubleSided (default true in TOML; docs/materials.md).
inline constexpr const char* kPbrDoubleSidedKey = "double_sided";

}  // namespace clpt
