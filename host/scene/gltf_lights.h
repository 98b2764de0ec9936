// KHR_lights_punctual (docs/gltf.md "What is read", lights): point, spot and directional lights placed by their
// nodes, in the physical units of scene.h PunctualLight (candela / 683 -> W/sr, lux / 683 -> W/m^2).
#pragma once

#include "scene/tinygltf_config.h"

#include <string>
#include <vector>

#include "scene/gltf_nodes.h"
#include "scene/scene.h"

namespace clpt {

// The lights the scene's nodes place, in node order (a light used by two nodes is two lights).
// `range_scale` multiplies each range (a [[gltf]] table's scale; 1 for a glTF scene);
// `file` becomes each light's `where`. Every light of the file is checked (GltfError).
std::vector<PunctualLight> convert_lights(const tinygltf::Model& model, const std::vector<NodeInstance>& nodes,
                                          double range_scale, const std::string& file);

}  // namespace clpt
