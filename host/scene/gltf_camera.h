// The view of a glTF scene (docs/gltf.md "The camera and the image size"): the first camera met in node order, or the
// one --camera names; the image size from --width/--height and the camera's aspect ratio; a view
// framing the scene's bounds when the file has no camera.
#pragma once

#include "scene/tinygltf_config.h"

#include <optional>
#include <string>
#include <vector>

#include "scene/gltf_loader.h"
#include "scene/gltf_nodes.h"
#include "scene/scene.h"

namespace clpt {

// Sets scene.camera and scene.settings.width/height from the scene's nodes (depth first, as
// scene_nodes returns them) and `view`; scene.meshes and scene.lights must be set (framing reads
// their bounds). Checks every camera of the file (GltfError); an unknown --camera is a usage
// error (ExitCode::Usage) listing the file's cameras. Warnings ("ELEMENT: MESSAGE") appended.
void set_view(const tinygltf::Model& model, const std::vector<NodeInstance>& nodes, const GltfView& view, Scene& scene,
              std::vector<std::string>& warnings);

}  // namespace clpt
